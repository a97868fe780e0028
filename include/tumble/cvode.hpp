#pragma once
// tumble's CVODE integration: everything that needs SUNDIALS CVODE and nothing of Boost (link
// tumble::cvode). tumble/integrate.hpp adds the explicit integrator and the front door.
//
//   tumble::Cvode<System>      the CVODE integrator of y' = f(t, y) (integrate/cvode.hpp)
//   tumble::CvodeSystem        what a system provides, and its optional members
//                              (integrate/system.hpp, which needs no SUNDIALS)
//   tumble::CvodeOptions       method, tolerances, step and solver options, projection
//   tumble::CvodeStatistics    counters (both in integrate/options.hpp, which needs no SUNDIALS)
//   tumble::SceneIntegrator    a Scene integrated with CVODE (charts, projection, events)
//   tumble::IntegrationError   any integrator's failure; tumble::CvodeError CVODE's, with its
//                              flag; tumble::RecoverableError for callbacks (integrate/errors.hpp)
//   the shared vocabulary      integrate/common.hpp

#include "tumble/integrate/common.hpp"
#include "tumble/integrate/cvode.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/options.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/integrate/system.hpp"
#include "tumble/tumble.hpp"
