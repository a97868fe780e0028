#pragma once
// tumble's integration module: everything that needs SUNDIALS CVODE (link tumble::cvode).
//
//   tumble::Cvode<System>      the CVODE integrator of y' = f(t, y) (integrate/cvode.hpp)
//   tumble::CvodeOptions       method, tolerances, step and solver options, projection
//   tumble::CvodeStatistics    counters
//   tumble::SceneIntegrator    a Scene integrated with CVODE (charts, projection, events)
//   tumble::IntegrationError   CVODE failure; tumble::RecoverableError for callbacks
//                              (integrate/errors.hpp, which needs no SUNDIALS)

#include "tumble/integrate/cvode.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/tumble.hpp"
