#pragma once
// tumble's model of the open spatial chain of chain_reference.hpp: six RigidBody<EulerParameters>
// framed at their centroids, six Revolute joints, uniform gravity, started from the second
// model's start (its positions, attitudes and velocities, computed in long double). Only the
// data and the start are taken from the second model; the dynamics are tumble's own (absolute
// coordinates, 30 constraint rows). Shared by tests/joint/spatial_chain.test.cpp and
// benchmarks/mechanisms/chain.cpp.

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "joint/chain_reference.hpp"
#include "tumble/tumble.hpp"

namespace chain_test {

struct TumbleChain {
  using Rod = tumble::RigidBody<tumble::EulerParameters>;
  using SceneT = tumble::Mechanism<tumble::Bodies<Rod>, tumble::Joints<tumble::Revolute>,
                                   tumble::Loads<tumble::UniformGravity>>;
  SceneT scene;
  std::vector<tumble::BodyId<Rod>> rods;

  TumbleChain() {
    using Eigen::Vector3d;
    using L = long double;
    const Chain<L> second;
    const Chain<L>::Kinematics k = second.kinematics(Chain<L>::start());
    const std::array<Eigen::Vector3d, data::n> a = axes<double>();
    const Vector3d top(0, 0, 0.5 * data::length);  // the hinge, from a rod's centroid
    for (std::size_t i = 0; i < data::n; ++i) {
      const Eigen::Matrix3d r = k.rotation[i].cast<double>();
      rods.push_back(scene.add(
          Rod(tumble::MassProperties<>::about_centroid(data::mass, rod_inertia<double>())),
          {.position = k.centroid[i].cast<double>(),
           .rotation = r,
           .velocity = k.velocity[i].cast<double>(),
           .omega = (k.rotation[i].transpose() * k.omega[i]).cast<double>()}));  // body axes
      scene.add_load(rods.back(), tumble::UniformGravity(Vector3d(0, 0, -data::g)));
      // Hinge i: rod i's top on its parent's bottom (the ground's origin for rod 0), about a_i,
      // whose components are the same in both rods' frames (the ground's is the world's).
      if (i == 0) {
        scene.add_joint(rods[0], tumble::ground,
                        tumble::Revolute(top, a[0], Vector3d::Zero(), a[0]));
      } else {
        scene.add_joint(rods[i], rods[i - 1], tumble::Revolute(top, a[i], -top, a[i]));
      }
    }
  }

  /// The last rod's far end, the tracked point (m).
  [[nodiscard]] Eigen::Vector3d tip(const tumble::SceneStateView& s) const {
    return tumble::position(scene, rods.back(), s) +
           tumble::rotation(scene, rods.back(), s) * Eigen::Vector3d(0, 0, -0.5 * data::length);
  }
};

}  // namespace chain_test
