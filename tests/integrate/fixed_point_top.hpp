#pragma once
// The Lagrange top of tests/support/lagrange_top.hpp held at its tip (ReferencePoint::fixed_point)
// and integrated in a scene of either state form by any integrator, checked against its closed
// form: what the fixed-point integration tests share (fixed_point*.test.cpp).
//
// Error bounds. The motion is quasi-periodic and neutrally stable: a local error committed at
// time t shifts the phase of the nutation by up to omega_n (t_end - t) times itself by t_end, so
// the period and the mean precession rate carry the bound tol x steps x (1 + omega_n t_end)
// (tumble::test::global_error_bound, whose factor 5 is the project's margin). The extremes of u,
// the energy and the momenta accumulate no phase: their errors are bounded by 5 tol x steps.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string_view>

#include <Eigen/Core>

#include "support/catch.hpp"
#include "support/lagrange_top.hpp"
#include "support/scene_fixtures.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble::test {

template <class P> using FixedBody = RigidBody<P, ReferencePoint::fixed_point>;
template <class P, StateForm Form = StateForm::generalized>
using TopScene = Scene<Bodies<FixedBody<P>>, Loads<UniformGravity>, Form>;

/// The top's pivot: on the vertical through O, so that p_psi = (H_O)_z.
inline const Eigen::Vector3d kTopPivot(0.0, 0.0, 0.3);

/// The top in a scene of form Form.
template <class P, StateForm Form> struct TopInScene {
  LagrangeTop top;
  TopScene<P, Form> scene;
  BodyId<FixedBody<P>> id;
  TopInScene() {
    id = scene.add(FixedBody<P>(top.mass_properties(), kTopPivot), top.initial_state(kTopPivot));
    scene.add_load(id, UniformGravity(top.gravity()));
  }
};

/// Integrates the top over four nutation periods with the integrator make(scene) (whose
/// advance(t) returns the state and whose statistics() count steps and chart switches) at
/// tolerance tol, and checks it against the closed form.
template <class P, StateForm Form, class Make>
void check_top(std::string_view method, double tol, Make&& make) {
  const TopInScene<P, Form> t;
  // [theta; thetadot] or [theta; omega]: nothing translational.
  REQUIRE(t.scene.size() == P::size + (Form == StateForm::generalized ? P::size : 3));
  auto integrator = make(t.scene);
  const int periods = 4;
  const auto m = measure_top(
      t.scene, t.id, t.top, t.scene.initial_state(),
      [&](double time) -> const SceneState& {
        integrator.advance(time);
        return integrator.state();
      },
      periods);
  const auto stats = integrator.statistics();
  const LagrangeTop& top = t.top;
  const auto [u2, u1, u3] = top.roots();
  const double t_end = periods * top.nutation_period();
  const double omega_n = 2 * std::numbers::pi / top.nutation_period();
  const double phase_bound = global_error_bound(tol, stats.steps, omega_n, t_end);
  const double level_bound = 5.0 * tol * static_cast<double>(stats.steps);

  const double e_umax = std::abs(m.u_max - u1), e_umin = std::abs(m.u_min - u2);
  const double e_period = std::abs(m.period - top.nutation_period()) / top.nutation_period();
  const double e_rate =
      std::abs(m.precession_rate - top.mean_precession_rate()) / top.mean_precession_rate();
  const char* form = Form == StateForm::generalized ? "generalized" : "quasi";
  INFO(P::name << " " << form << " " << method << ": " << stats.steps << " steps, "
               << stats.chart_switches << " chart switches; |u_max - u1| = " << e_umax
               << ", |u_min - u2| = " << e_umin << ", period " << e_period << ", precession "
               << e_rate << ", energy " << m.energy_drift << ", p_psi " << m.p_psi_drift
               << ", p_phi " << m.p_phi_drift << "; bounds: level " << level_bound << ", phase "
               << phase_bound);
  if (std::getenv("TUMBLE_TEST_REPORT") != nullptr) {
    std::printf("top %-27.*s %-11s %-10.*s steps %6ld switches %3ld |du1| %.1e |du2| %.1e "
                "period %.1e precession %.1e energy %.1e p_psi %.1e p_phi %.1e\n",
                static_cast<int>(P::name.size()), P::name.data(), form,
                static_cast<int>(method.size()), method.data(), static_cast<long>(stats.steps),
                static_cast<long>(stats.chart_switches), e_umax, e_umin, e_period, e_rate,
                m.energy_drift, m.p_psi_drift, m.p_phi_drift);
  }
  // u between the two roots in [-1, 1] of the cubic, touching both.
  CHECK(u2 > -1.0);
  CHECK(u1 < 1.0);
  CHECK(u3 > 1.0);
  CHECK(e_umax < level_bound);
  CHECK(e_umin < level_bound);
  CHECK(e_period < phase_bound);
  CHECK(e_rate < phase_bound);
  CHECK(m.energy_drift < level_bound);
  CHECK(m.p_psi_drift < level_bound);
  CHECK(m.p_phi_drift < level_bound);
}

}  // namespace tumble::test
