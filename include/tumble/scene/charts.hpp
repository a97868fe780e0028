#pragma once
// Chart switching: how a scene's three-parameter bodies leave a chart before its singularity
// (the mechanism and its thresholds: chart.hpp). Each such body has one root function, the
// distance to the singularity minus the switch distance; at a root, or whenever a state starts
// inside the switch zone, the chart is re-centered:
//   R0' = R0 R(theta) R(theta_c)^T,  theta' = theta_c,  thetadot' = P::thetadot(theta_c, omega),
// or, for MRP, switched to the shadow set (same base). The attitude R0 R(theta) and omega are
// unchanged. In the quasi-velocity state form (state.hpp) only theta and the base change: v and
// omega are stored as such, so a switch leaves them untouched, to the last bit. The chart base is
// part of the state (state.hpp), so these functions change both the continuous vector y and the
// bases, and nothing in the scene.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <type_traits>

#include "tumble/core/types.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

/// g[i] = distance to the singularity - switch distance (rad) of the i-th body with a singular
/// chart (Scene::chart_bodies() order). CVODE watches these for falling zero crossings.
template <class SceneT, class Y, class G> void chart_roots(const SceneT& scene, const Y& y, G&& g) {
  int i = 0;
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    if constexpr (Chart<P>::has_singularity) {
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
      g[i++] = P::singularity_distance(th) - e.switch_distance;
    }
  });
}

/// Leaves the chart of body e in the state (y, its base): re-centers it, or takes the MRP
/// shadow set.
template <class Entry, class Y> void leave_chart(const Entry& e, Y& y, Matrix3<double>& base) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  using P = typename Body::Param;
  static_assert(Chart<P>::has_singularity, "only three-parameter sets leave their chart");
  const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
  typename Body::Theta th_new;
  if constexpr (Chart<P>::uses_shadow_set) {
    th_new = P::shadow(th);
  } else {
    const typename Body::Theta c = Chart<P>::center();
    const Matrix3<double> b = base * P::rotation(th) * P::rotation(c).transpose();
    // Re-orthonormalized through the quaternion, so rounding does not accumulate over switches.
    base = EulerParameters::rotation(EulerParameters::from_rotation(b));
    th_new = c;
  }
  y.template segment<Body::n_theta>(e.offset + e.theta_at) = th_new;
  if constexpr (!Entry::quasi) {  // thetadot' for the same omega = G(theta) thetadot
    const Vector3<double> w = P::G(th) * y.template segment<Body::n_theta>(e.rates + e.theta_at);
    y.template segment<Body::n_theta>(e.rates + e.theta_at) = P::thetadot(th_new, w);
  }
}

/// For a trial step from y0 to y1 of an integrator without root finding: 1 when no chart root at
/// y1 is below its limit (deep[i] < 0: the part of the switch zone a step may end in); else the
/// fraction of the step to retry with, for each chart that went too deep the one that would end
/// the step in the middle of the allowed part if the root were linear in t (clamped to 0.1-0.9;
/// 0.5 when the roots do not bracket it). g1, g0: scratch of the chart bodies' count.
template <class SceneT, class Y0, class Y1, class G>
double chart_step_fraction(const SceneT& scene, const Y0& y0, const Y1& y1,
                           std::span<const double> deep, G& g0, G& g1) {
  double fraction = 1.0;
  if (deep.empty()) {
    return fraction;
  }
  chart_roots(scene, y1, g1);
  bool have_g0 = false;
  for (std::size_t i = 0; i < deep.size(); ++i) {
    if (!(g1[i] >= deep[i])) {
      if (!have_g0) {
        chart_roots(scene, y0, g0);
        have_g0 = true;
      }
      const double f = (g0[i] - 0.5 * deep[i]) / (g0[i] - g1[i]);
      fraction = std::min(fraction, std::isfinite(f) ? std::clamp(f, 0.1, 0.9) : 0.5);
    }
  }
  return fraction;
}

/// Leaves the chart of every body whose root was found (which[i] != 0 for the i-th chart body,
/// as in chart_roots). on_switch(id) is called for each. Returns the number of switches.
template <class SceneT, class Y, class OnSwitch>
int leave_charts(const SceneT& scene, Y&& y, std::span<Matrix3<double>> base, const int* which,
                 OnSwitch&& on_switch) {
  int i = 0, n = 0;
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    if constexpr (Chart<typename Body::Param>::has_singularity) {
      if (which[i++] != 0) {
        leave_chart(e, y, base[e.id]);
        on_switch(e.id);
        ++n;
      }
    }
  });
  return n;
}

/// Re-centers every chart that is closer to its singularity than its switch distance (at the
/// start of a run and after the user changed the state). on_switch(id) is called for each.
/// Returns the number of switches.
template <class SceneT, class Y, class OnSwitch>
int recenter_charts(const SceneT& scene, Y&& y, std::span<Matrix3<double>> base,
                    OnSwitch&& on_switch) {
  int n = 0;
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    if constexpr (Chart<P>::has_singularity) {
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
      if (P::singularity_distance(th) < e.switch_distance) {
        leave_chart(e, y, base[e.id]);
        on_switch(e.id);
        ++n;
      }
    }
  });
  return n;
}

/// The same on an owned state, uncounted.
template <class SceneT> int recenter_charts(const SceneT& scene, SceneState& s) {
  return recenter_charts(scene, s.y, std::span<Matrix3<double>>(s.base), [](int) {});
}

}  // namespace tumble
