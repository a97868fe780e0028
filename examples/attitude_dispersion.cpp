// Attitude dispersion of a tumbling satellite: a Monte Carlo ensemble across the cores.
//
// Problem: a satellite with principal moments of inertia I = diag(1, 2, 3) kg m^2 tumbles from
// omega0 = (0.1, 2, 0.05) rad/s (body frame), nearly about its intermediate axis, so it flips
// (the Dzhanibekov effect) and small uncertainties grow. Both are uncertain: each run draws
// I_x and I_y within +-3 %, I_z within 3 % below I_x + I_y (the nominal body sits on the
// triangle inequality I_z <= I_x + I_y, a flat plate; no physical body lies beyond it), and each
// omega0 component from a normal distribution with a 1 % standard deviation. After 50 s, the
// pointing error of a run is the angle between its body x axis (a boresight) and the nominal
// run's. The runs are done in blocks, in parallel (tumble::integrate_variants: a scene per run,
// since the inertia differs), with progress after each block; then a summary table, a CSV of
// every run and a PNG histogram of the pointing error.
//
// Equations: torque-free rigid body, I omega' = -omega x I omega (reference chapter Eq. 1.33 with
// Q = 0), MRP in the quasi-velocity form, integrated by Boost.Odeint (Fehlberg 7(8), rtol = atol
// = 1e-10). Units: SI (kg m^2, rad/s, s); the pointing error in degrees.
//
// Run: ./attitude_dispersion [output folder] [runs]   (defaults: the current folder, 10000)
// Writes attitude_dispersion.csv and attitude_dispersion.png into the output folder.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/png_plot.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/ensemble/variants.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Body = tumble::RigidBody<tumble::ModifiedRodriguesParameters>;
using Scene =
    tumble::Scene<tumble::Bodies<Body>, tumble::Loads<>, tumble::StateForm::quasi_velocities>;
constexpr int kStates = 3 + 3 + 6;  // [r; sigma; v; omega]
constexpr double kEnd = 50.0;       // s
const Eigen::Vector3d kInertia(1.0, 2.0, 3.0);
const Eigen::Vector3d kOmega(0.1, 2.0, 0.05);

/// A run's draw: its principal moments and initial rates (run 0 of none: the nominal).
struct Draw {
  Eigen::Vector3d inertia;
  Eigen::Vector3d omega;
};

/// Run i's dispersion, from a generator seeded with i: the same whatever thread runs it.
Draw draw(std::size_t i) {
  std::mt19937_64 rng(0x5eed0000u + i);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  Draw d;
  d.inertia.x() = kInertia.x() * (1.0 + 0.03 * u(rng));
  d.inertia.y() = kInertia.y() * (1.0 + 0.03 * u(rng));
  d.inertia.z() = (d.inertia.x() + d.inertia.y()) * (1.0 - 0.03 * std::abs(u(rng)));
  for (int k = 0; k < 3; ++k) {
    d.omega(k) = kOmega(k) * (1.0 + 0.01 * n(rng));
  }
  return d;
}

Scene make_scene(const Draw& d) {
  Scene scene;
  scene.add(Body(tumble::MassProperties<double>::about_centroid(1.0, d.inertia.asDiagonal())),
            {.omega = d.omega});
  return scene;
}

const auto make_integrator = [](const Scene& s, double t0, const tumble::SceneState& y0) {
  tumble::OdeintOptions options;
  options.rtol = 1e-10;
  options.atol = 1e-10;
  return tumble::OdeintIntegrator<Scene, kStates>(s, t0, y0, options);
};

/// The body x axis in the inertial frame (the first column of R, r_F = R r_f).
Eigen::Vector3d boresight(const Scene& scene, const tumble::SceneState& s) {
  return tumble::rotation(scene, tumble::BodyId<Body>{0, 0}, s).col(0);
}

double percentile(const std::vector<double>& sorted, double p) {  // linear between ranks
  const double at = p * static_cast<double>(sorted.size() - 1);
  const auto k = static_cast<std::size_t>(at);
  const double f = at - static_cast<double>(k);
  return k + 1 < sorted.size() ? sorted[k] * (1 - f) + sorted[k + 1] * f : sorted[k];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : ".";
  const long requested = argc > 2 ? std::atol(argv[2]) : 10000;
  if (requested < 1) {
    std::fprintf(stderr, "usage: %s [output folder] [runs >= 1]\n", argv[0]);
    return 2;
  }
  const auto runs = static_cast<std::size_t>(requested);
  const std::vector<double> times{kEnd};

  // The nominal run, once, in this thread.
  const Scene nominal = make_scene({kInertia, kOmega});
  auto integrator = make_integrator(nominal, 0.0, nominal.initial_state());
  integrator.advance(kEnd);
  const Eigen::Vector3d x_nominal = boresight(nominal, integrator.state());

  // The dispersed runs, in 10 blocks, each across the cores (threads = 0: TBB's choice).
  const tumble::EnsembleOptions options{.threads = 0, .grain = 8};
  std::vector<double> error(runs, std::nan(""));
  std::vector<tumble::RunError> failed;
  const std::size_t block = std::max<std::size_t>(1, (runs + 9) / 10);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t first = 0; first < runs; first += block) {
    const std::size_t n = std::min(block, runs - first);
    const auto results = tumble::integrate_variants<double>(
        n, [&](std::size_t k) { return make_scene(draw(first + k)); }, make_integrator, 0.0, times,
        [&](double& deg, std::size_t, double, const tumble::SceneState& s, const Scene& scene) {
          const double c = std::clamp(boresight(scene, s).dot(x_nominal), -1.0, 1.0);
          deg = std::acos(c) * 180.0 / std::numbers::pi;
        },
        options);
    for (std::size_t k = 0; k < n; ++k) {
      if (results[k].ok()) {
        error[first + k] = results[k].value();
      } else {
        failed.push_back({first + k, results[k].error().message});
      }
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("  runs %6zu-%6zu done: %6zu of %zu, %5.1f s, %8.0f runs/s\n", first, first + n - 1,
                first + n, runs, s, static_cast<double>(first + n) / s);
    std::fflush(stdout);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const tumble::RunError& e : failed) {
    std::printf("run %zu failed: %s\n", e.run, e.message.c_str());
  }

  // The summary of the runs that finished.
  std::vector<double> ok;
  for (double e : error) {
    if (!std::isnan(e)) {
      ok.push_back(e);
    }
  }
  if (ok.empty()) {
    std::printf("no run finished\n");
    return 1;
  }
  std::sort(ok.begin(), ok.end());
  double mean = 0.0;
  for (double e : ok) {
    mean += e;
  }
  mean /= static_cast<double>(ok.size());
  double var = 0.0;
  for (double e : ok) {
    var += (e - mean) * (e - mean);
  }
  const double sd = ok.size() > 1 ? std::sqrt(var / static_cast<double>(ok.size() - 1)) : 0.0;
  std::printf("\npointing error of the body x axis after %.0f s, against the nominal run (deg)\n",
              kEnd);
  std::printf("  %-22s %12zu\n", "runs", runs);
  std::printf("  %-22s %12zu\n", "failed", failed.size());
  std::printf("  %-22s %12.4f\n", "mean", mean);
  std::printf("  %-22s %12.4f\n", "std", sd);
  std::printf("  %-22s %12.4f\n", "min", ok.front());
  for (const double p : {0.05, 0.5, 0.9, 0.95, 0.99}) {
    std::printf("  %-22s %12.4f\n", ("percentile " + std::to_string(int(p * 100))).c_str(),
                percentile(ok, p));
  }
  std::printf("  %-22s %12.4f\n", "max", ok.back());
  std::printf("  %-22s %12.2f\n", "wall time (s)", wall);
  std::printf("  %-22s %12.0f\n", "runs/s", static_cast<double>(runs) / wall);
  std::printf("  %-22s %12u\n", "threads (all cores)", std::thread::hardware_concurrency());

  // Every run as CSV; the histogram as a PNG (40 bins from 0 to the largest error).
  std::ofstream csv(out + "/attitude_dispersion.csv");
  csv << "run,I_x_kg_m2,I_y_kg_m2,I_z_kg_m2,omega_x_rad_s,omega_y_rad_s,omega_z_rad_s,"
         "pointing_error_deg\n";
  csv.precision(17);
  for (std::size_t i = 0; i < runs; ++i) {
    const Draw d = draw(i);
    csv << i << ',' << d.inertia.x() << ',' << d.inertia.y() << ',' << d.inertia.z() << ','
        << d.omega.x() << ',' << d.omega.y() << ',' << d.omega.z() << ',' << error[i] << '\n';
  }
  const int bins = 40;
  const double width = ok.back() > 0 ? ok.back() / bins : 1.0;
  std::vector<double> count(bins, 0.0);
  for (double e : ok) {
    count[std::min(bins - 1, static_cast<int>(e / width))] += 1.0;
  }
  std::vector<double> x{0.0}, y{0.0};  // the histogram's outline, a step curve
  for (int b = 0; b < bins; ++b) {
    x.insert(x.end(), {b * width, (b + 1) * width});
    y.insert(y.end(), {count[b], count[b]});
  }
  x.push_back(bins * width);
  y.push_back(0.0);
  tumble_examples::PngPlot plot(
      900, 500,
      "Tumbling satellite: pointing error after 50 s, " + std::to_string(ok.size()) + " runs");
  plot.set_labels("pointing error of the x axis (deg)", "runs per bin");
  plot.add(x, y, {30, 60, 200}, "histogram");
  plot.write(out + "/attitude_dispersion.png");
  std::printf("wrote %s/attitude_dispersion.csv and %s/attitude_dispersion.png\n", out.c_str(),
              out.c_str());
  return failed.empty() ? 0 : 1;
}
