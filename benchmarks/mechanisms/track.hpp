#pragma once
// tumble_bench, study (e): the error measure of a point's track (A01's bob, A04's P3), shared by
// tumble's runs (mechanisms/run.hpp) and the peers' (peers/mujoco_mechanisms.cpp), so that every
// row of a problem is measured by the same code against the same reference. Eigen only.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace tumble::bench {

/// record(k, p) at output k, then measure(), the largest distance from the reference over the
/// outputs, NaN when an output was not recorded (as A03's measure); it clears the track for the
/// next run.
class PointTrackError {
 public:
  explicit PointTrackError(std::vector<Eigen::Vector3d> reference)
      : reference_(std::move(reference)), track_(reference_.size(), missing()) {}

  void record(std::size_t k, const Eigen::Vector3d& p) { track_[k] = p; }

  double measure() {
    double err = 0;
    for (std::size_t k = 0; k < reference_.size(); ++k) {
      const double d = (track_[k] - reference_[k]).norm();
      if (std::isnan(d)) {  // an output not recorded
        err = d;
        break;
      }
      err = std::max(err, d);
    }
    std::fill(track_.begin(), track_.end(), missing());
    return err;
  }

 private:
  static Eigen::Vector3d missing() {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  std::vector<Eigen::Vector3d> reference_, track_;
};

}  // namespace tumble::bench
