#pragma once
// tumble_micro: what every translation unit of the per-call benchmarks registers for a
// parameterization P (micro/micro.cpp lists the benchmarks). Each family of parameterizations is
// registered from a source of its own (micro/params_*.cpp), so that each is compiled as a user's
// translation unit with one or two body types is: in one unit with all sixteen, GCC 12 stopped
// inlining the small functions of the hot path (omega, Euler's equations, the 3x3 products):
// Euler parameters' qddot took 1.39x its time in a unit of its own, the hand-written floor 1.24x
// (docs/benchmarks/per-call.md, 2026-11-26).

#include <string>

#include "micro/common.hpp"

namespace tumble::bench {

template <class P> void register_orientation() {
  const std::string name(P::name);
  using Body = RigidBody<P, ReferencePoint::centroid, double>;
  add("rotation/" + name, [](benchmark::State& st) {
    static const States<Body> s;
    run_cycling(st, [&](std::size_t i) { return P::rotation(Body::theta(s.q[i])); });
  });
  add("G/" + name, [](benchmark::State& st) {
    static const States<Body> s;
    run_cycling(st, [&](std::size_t i) { return P::G(Body::theta(s.q[i])); });
  });
}

template <class P, ReferencePoint Ref> void register_body() {
  using Body = RigidBody<P, Ref, double>;
  const std::string suffix = std::string("/") + std::string(P::name) + "/" + ref_name(Ref);
  add("mass_matrix" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling(st, [&](std::size_t i) { return body.mass_matrix(s.q[i]); });
  });
  add("centrifugal_coriolis" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling(st, [&](std::size_t i) { return body.centrifugal_coriolis(s.q[i], s.qdot[i]); });
  });
  add("generalized_force" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    const LoadSet l;
    run_cycling(st, [&](std::size_t i) {
      return tumble::generalized_force(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
    });
  });
  add("qddot" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling_inlined(
        st, [&](std::size_t i) { return body.accelerations(s.q[i], s.qdot[i], s.wrench[i]); });
  });
  add("qddot_loads" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    const LoadSet l;
    run_cycling_inlined(st, [&](std::size_t i) {
      return tumble::accelerations(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
    });
  });
}

template <class... P> void register_all() {
  (register_orientation<P>(), ...);
  (register_body<P, ReferencePoint::centroid>(), ...);
  (register_body<P, ReferencePoint::offset>(), ...);
}

}  // namespace tumble::bench
