#pragma once
// tumble: rigid-body equations of motion in generalized coordinates (Eigen only).
// For time integration with SUNDIALS CVODE include "tumble/cvode.hpp" and link tumble::cvode.
//
//   orientation/   EulerAngles<a1,a2,a3> (12 aliases), EulerParameters, RodriguesParameters,
//                  ModifiedRodriguesParameters, RotationVector; the Orientation concept; convert
//   body/          MassProperties, RigidBody<P, ReferencePoint, Scalar>, Wrench, kinematics
//   force/         UniformGravity, PointForce, BodyMoment, SpringDamper, SpringDamperBetween,
//                  UserForce, UserCoupling; total_wrench, generalized_force, accelerations
//   joint/         Spherical, Revolute, Universal, Cylindrical, Prismatic, Weld, Distance,
//                  UserJoint<M>; the JointElement concept and the primitives they are built of
//   scene/         Scene<Bodies<...>, Loads<...>> (the model), SceneState (y and chart bases),
//                  SceneWorkspace; rhs, jacobian (Jet<N> automatic differentiation; dense or
//                  BandMatrixMap), BlockPreconditioner, chart switching, projection, observables,
//                  angular accelerations and reaction forces (accelerations.hpp); mechanisms
//                  (Scene<..., Joints<...>> or Mechanism<...>): the constraint solve
//                  (joints.hpp), projection, assembly, residuals, joint reactions (assembly.hpp)

#include "tumble/body/kinematics.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/body/wrench.hpp"
#include "tumble/core/band_matrix.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/jet.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/loads.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/joint/concept.hpp"
#include "tumble/joint/cylindrical.hpp"
#include "tumble/joint/distance.hpp"
#include "tumble/joint/prismatic.hpp"
#include "tumble/joint/revolute.hpp"
#include "tumble/joint/spherical.hpp"
#include "tumble/joint/universal.hpp"
#include "tumble/joint/user_joint.hpp"
#include "tumble/joint/weld.hpp"
#include "tumble/orientation/concept.hpp"
#include "tumble/orientation/euler_angles.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/orientation/rodrigues.hpp"
#include "tumble/orientation/rotation_vector.hpp"
#include "tumble/scene/accelerations.hpp"
#include "tumble/scene/assembly.hpp"
#include "tumble/scene/attitude_only.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/jacobian.hpp"
#include "tumble/scene/joints.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/preconditioner.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"
