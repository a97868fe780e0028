#pragma once
// tumble's integration, all of it: the front door and both integrators (link tumble::cvode and
// tumble::odeint, i.e. SUNDIALS CVODE and the Boost headers).
//
//   tumble::integrate(scene, t0, times, observer, {.rtol = ...})
//                              the front door: the method chosen, a report of what ran and why
//   tumble::AutoIntegrator     the same as an integrator (advance, integrate, reset, save, ...)
//                              (integrate/auto_integrator.hpp)
//   tumble::OdeintIntegrator   Boost.Odeint's explicit pairs (integrate/explicit_integrator.hpp)
//   tumble::SceneIntegrator    CVODE, Adams or BDF (integrate/scene_integrator.hpp)
//   the shared vocabulary      rtol, atol, max_steps, ...; the statistics' names
//                              (integrate/common.hpp); IntegrationError and its kinds
//                              (integrate/errors.hpp)
// tumble/cvode.hpp is the CVODE part alone (no Boost), for builds without Odeint.

#include "tumble/cvode.hpp"
#include "tumble/integrate/auto_integrator.hpp"
#include "tumble/integrate/common.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/integrate/explicit_options.hpp"
