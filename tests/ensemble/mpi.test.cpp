// tumble::MpiEnsemble (include/tumble/ensemble/mpi.hpp), run by ctest under mpirun with 1 and 2
// ranks. Every rank runs the same test cases in the same order (the collective calls must match);
// the checks are made at rank 0 after the collective calls, against expectations that use no MPI:
//  - the tumbling body (I = diag(1, 2, 3), omega0 = (0.1, 2, 0.05) rad/s dispersed per run, MRP in
//    the quasi-velocity form) integrated by OdeintIntegrator: every run's result at rank 0
//    bitwise equal to a one-process Ensemble's (2 threads), for run counts that do not divide
//    evenly, fewer runs than ranks and none, on 1 and 2 threads per rank;
//  - failing runs (initial(i) throws, the observer throws) reported at rank 0 with their index
//    and message, whichever rank ran them, the other runs' results kept and bitwise equal;
//  - mpi_integrate_variants (a scene per run: dispersed inertia) bitwise equal to
//    integrate_variants on one process, a failing scene reported with its index;
//  - MpiEnsemble::fold in blocks bitwise equal to Ensemble::fold and to fold_runs over the
//    one-process results in run order (a non-associative floating-point sum), errors included;
//  - statistics(): the runs and failures over all ranks on every rank, each rank's runs, this
//    rank's runs, failures and threads, after integrate and fold;
//  - misuse: no MPI (made before MPI_Init), bad times, block 0 and run counts that differ between
//    ranks throw on every rank instead of hanging.

#include "tumble/ensemble/mpi.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <mpi.h>

#if TUMBLE_CATCH_V3
#include <catch2/catch_session.hpp>
#else
#define CATCH_CONFIG_RUNNER
#endif
#include "support/catch.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/ensemble/ensemble.hpp"
#include "tumble/ensemble/variants.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Vector3d;
using tumble::RunOutcome;
using tumble::SceneState;

using Body = tumble::RigidBody<tumble::ModifiedRodriguesParameters>;
using SceneT =
    tumble::Scene<tumble::Bodies<Body>, tumble::Loads<>, tumble::StateForm::quasi_velocities>;
using Odeint = tumble::OdeintIntegrator<SceneT, 12>;

const Vector3d kOmega(0.1, 2.0, 0.05);
const std::vector<double> kTimes{0.0, 4.0, 8.0};

/// What a run keeps, as plain numbers (trivially copyable, unlike Eigen's matrices).
struct Final {
  std::array<double, 9> attitude{};
  std::array<double, 3> omega{};
  int outputs = 0;
};

bool same(const Final& a, const Final& b) {  // bitwise: == on every double
  return a.attitude == b.attitude && a.omega == b.omega && a.outputs == b.outputs;
}

/// Set before MPI_Init by main(): the error an MpiEnsemble made then threw, if any.
std::string g_before_init;

struct Tumbling {
  SceneT scene;
  tumble::BodyId<Body> b;

  Tumbling() {
    b = scene.add(Body(tumble::MassProperties<double>::about_centroid(
                      1.0, Vector3d(1.0, 2.0, 3.0).asDiagonal())),
                  {.omega = kOmega});
  }
  /// Run i's initial state: omega0 dispersed by up to 2 % per component.
  SceneState initial(std::size_t i) const {
    const double x = static_cast<double>(i);
    SceneState s = scene.initial_state();
    tumble::set_velocity(
        scene, b, s, Vector3d::Zero(),
        kOmega.cwiseProduct(Vector3d::Ones() + 0.02 * Vector3d(std::sin(1.1 * x), std::cos(0.7 * x),
                                                               std::sin(0.3 * x))));
    return s;
  }
  auto observer() const {
    return [this](Final& f, std::size_t, double, const SceneState& s) {
      Eigen::Map<Eigen::Matrix3d>(f.attitude.data()) = tumble::rotation(scene, b, s);
      Eigen::Map<Vector3d>(f.omega.data()) = tumble::omega(scene, b, s);
      ++f.outputs;
    };
  }
};

const auto make = [](const SceneT& s, double t0, const SceneState& y0) {
  tumble::OdeintOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-10;
  return Odeint(s, t0, y0, o);
};

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

/// Sum of the first attitude entry and the omega components, in fold order: not associative, so
/// any other order shows in the last bits.
double add(double acc, std::size_t, const Final& f) {
  return acc + f.attitude[0] + f.omega[0] * 1e-3 + f.omega[2] * 1e3;
}

}  // namespace

TEST_CASE("mpi: rank 0 holds every run, bitwise the one-process Ensemble's", "[ensemble][mpi]") {
  const Tumbling t;
  const auto initial = [&](std::size_t i) { return t.initial(i); };
  const tumble::Ensemble reference(t.scene, make, {.threads = 2});
  for (const int threads : {1, 2}) {
    const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = threads});
    for (const std::size_t runs : {std::size_t{13}, std::size_t{1}, std::size_t{0}}) {
      const auto got = ensemble.integrate<Final>(runs, initial, 0.0, kTimes, t.observer());
      if (ensemble.rank() != 0) {
        CHECK(got.empty());
        continue;
      }
      const auto want = reference.integrate<Final>(runs, initial, 0.0, kTimes, t.observer());
      INFO(threads << " threads per rank, " << ensemble.ranks() << " ranks, " << runs << " runs");
      REQUIRE(got.size() == runs);
      for (std::size_t i = 0; i < runs; ++i) {
        INFO("run " << i);
        REQUIRE(got[i].ok());
        CHECK(got[i].value().outputs == 3);
        CHECK(same(got[i].value(), want[i].value()));
      }
    }
  }
}

TEST_CASE("mpi: the blocks of the ranks are contiguous and cover the runs", "[ensemble][mpi]") {
  const Tumbling t;
  const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = 1});
  for (const std::size_t runs : {0, 1, 2, 7, 13}) {
    std::size_t next = 0;
    for (int r = 0; r < ensemble.ranks(); ++r) {
      const auto [b, e] = ensemble.runs_of_rank(runs, r);
      CHECK(b == next);
      CHECK(e >= b);
      CHECK(e - b <= runs / static_cast<std::size_t>(ensemble.ranks()) + 1);
      next = e;
    }
    CHECK(next == runs);
  }
}

TEST_CASE("mpi: failing runs reach rank 0 with their index and message, the others kept",
          "[ensemble][mpi]") {
  const Tumbling t;
  // Run 9 fails before it starts (on the last rank when there are 2), run 2 in its observer.
  const auto initial = [&](std::size_t i) {
    if (i == 9) {
      throw std::runtime_error("no initial state for run 9");
    }
    return t.initial(i);
  };
  const auto observe = [&](Final& f, std::size_t i, double time, const SceneState& s) {
    if (i == 2 && time > 5.0) {
      throw std::domain_error("observer gave up on run 2");
    }
    t.observer()(f, i, time, s);
  };
  const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = 2});
  const std::size_t runs = 12;
  const auto got = ensemble.integrate<Final>(runs, initial, 0.0, kTimes, observe);
  if (ensemble.rank() == 0) {
    REQUIRE(got.size() == runs);
    const auto errors = tumble::failures(got);
    REQUIRE(errors.size() == 2);
    CHECK(errors[0].run == 2);
    CHECK(errors[0].message == "observer gave up on run 2");
    CHECK(errors[1].run == 9);
    CHECK(errors[1].message == "no initial state for run 9");
    const tumble::Ensemble reference(t.scene, make, {.threads = 2});
    const auto want = reference.integrate<Final>(runs, initial, 0.0, kTimes, observe);
    for (std::size_t i = 0; i < runs; ++i) {
      INFO("run " << i);
      REQUIRE(got[i].ok() == want[i].ok());
      if (got[i].ok()) {
        CHECK(same(got[i].value(), want[i].value()));
      }
    }
  }
}

TEST_CASE("mpi: statistics say the ranks, each rank's runs and the failures, on every rank",
          "[ensemble][mpi]") {
  const Tumbling t;
  const auto initial = [&](std::size_t i) {  // runs 1 and 11 fail: one on each rank of 2
    if (i == 1 || i == 11) {
      throw std::runtime_error("no initial state");
    }
    return t.initial(i);
  };
  const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = 2});
  CHECK(ensemble.statistics().runs == 0);  // no call yet
  CHECK(ensemble.statistics().runs_per_rank.empty());
  const std::size_t runs = 13;
  const auto check = [&](std::size_t failed, const char* call) {
    INFO(call << ", rank " << ensemble.rank() << " of " << ensemble.ranks());
    const tumble::MpiEnsembleStatistics st = ensemble.statistics();
    CHECK(st.runs == runs);
    CHECK(st.failed == failed);  // over all ranks, on every rank
    CHECK(st.ranks == ensemble.ranks());
    REQUIRE(st.runs_per_rank.size() == static_cast<std::size_t>(ensemble.ranks()));
    std::size_t sum = 0;
    for (const std::size_t n : st.runs_per_rank) {
      sum += n;
    }
    CHECK(sum == runs);
    CHECK(st.this_rank.runs == st.runs_per_rank[static_cast<std::size_t>(ensemble.rank())]);
    // This rank's failures: those of its runs (runs_of_rank, one block of 13 for integrate).
    std::size_t mine = 0;
    const auto [b, e] = ensemble.runs_of_rank(runs, ensemble.rank());
    for (const std::size_t i : {std::size_t{1}, std::size_t{11}}) {
      mine += (failed > 0 && i >= b && i < e) ? 1 : 0;
    }
    if (std::string(call) == "integrate") {
      CHECK(st.this_rank.runs == e - b);
      CHECK(st.this_rank.failed == mine);
    }
    CHECK(st.this_rank.threads == tumble::Ensemble(t.scene, make, {.threads = 2}).threads());
    CHECK(st.this_rank.threads_used >= 1);
    CHECK(st.this_rank.threads_used <= st.this_rank.threads);
  };
  (void)ensemble.integrate<Final>(runs, initial, 0.0, kTimes, t.observer());
  check(2, "integrate");
  (void)ensemble.fold<Final>(runs, initial, 0.0, kTimes, t.observer(), 0.0, add, 4);
  check(2, "fold");
  const auto fine = [&](std::size_t i) { return t.initial(i); };
  (void)ensemble.integrate<Final>(runs, fine, 0.0, kTimes, t.observer());
  check(0, "integrate");
}

TEST_CASE("mpi: per-run scenes over the ranks equal integrate_variants to the bit",
          "[ensemble][mpi]") {
  // Run i's scene: the inertia dispersed by up to 2 % (I_z kept below I_x + I_y); run 10's
  // scene cannot be built (on the last rank when there are 2).
  const auto make_scene = [](std::size_t i) {
    if (i == 10) {
      throw std::invalid_argument("no scene for run 10");
    }
    const double x = static_cast<double>(i);
    const double ix = 1.0 + 0.02 * std::sin(x), iy = 2.0 + 0.04 * std::cos(x);
    const Vector3d inertia(ix, iy, (ix + iy) * (1.0 - 0.02 * std::abs(std::sin(2.0 * x))));
    SceneT scene;
    scene.add(Body(tumble::MassProperties<double>::about_centroid(1.0, inertia.asDiagonal())),
              {.omega = kOmega});
    return scene;
  };
  const auto observe = [](Final& f, std::size_t, double, const SceneState& s, const SceneT& sc) {
    const tumble::BodyId<Body> b{0, 0};
    Eigen::Map<Eigen::Matrix3d>(f.attitude.data()) = tumble::rotation(sc, b, s);
    Eigen::Map<Vector3d>(f.omega.data()) = tumble::omega(sc, b, s);
    ++f.outputs;
  };
  const std::size_t runs = 13;
  const auto got = tumble::mpi_integrate_variants<Final>(runs, make_scene, make, 0.0, kTimes,
                                                         observe, {.threads = 2});
  if (rank() == 0) {
    const auto want = tumble::integrate_variants<Final>(runs, make_scene, make, 0.0, kTimes,
                                                        observe, {.threads = 2});
    REQUIRE(got.size() == runs);
    for (std::size_t i = 0; i < runs; ++i) {
      INFO("run " << i);
      if (i == 10) {
        REQUIRE(got[i].failed());
        CHECK(got[i].error().run == 10);
        CHECK(got[i].error().message == "no scene for run 10");
      } else {
        REQUIRE(got[i].ok());
        CHECK(got[i].value().outputs == 3);
        CHECK(same(got[i].value(), want[i].value()));
      }
    }
  } else {
    CHECK(got.empty());
  }
}

TEST_CASE("mpi: fold equals the one-process fold and fold_runs to the bit", "[ensemble][mpi]") {
  const Tumbling t;
  const auto initial = [&](std::size_t i) {
    if (i == 6) {
      throw std::runtime_error("run 6 fails");
    }
    return t.initial(i);
  };
  const std::size_t runs = 15;
  for (const std::size_t block : {std::size_t{4}, std::size_t{64}}) {
    const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = 2});
    const auto got =
        ensemble.fold<Final>(runs, initial, 0.0, kTimes, t.observer(), 0.0, add, block);
    if (ensemble.rank() != 0) {
      CHECK(got.completed == 0);
      CHECK(got.value == 0.0);
      continue;
    }
    INFO("block " << block);
    const tumble::Ensemble reference(t.scene, make, {.threads = 1});
    const auto want =
        reference.fold<Final>(runs, initial, 0.0, kTimes, t.observer(), 0.0, add, block);
    const auto all = reference.integrate<Final>(runs, initial, 0.0, kTimes, t.observer());
    double serial = 0.0;
    for (std::size_t i = 0; i < runs; ++i) {  // the serial fold, written out
      if (all[i].ok()) {
        serial = add(serial, i, all[i].value());
      }
    }
    CHECK(got.value == want.value);
    CHECK(got.value == serial);
    CHECK(got.value == tumble::fold_runs(all, 0.0, add));
    CHECK(got.completed == runs - 1);
    REQUIRE(got.errors.size() == 1);
    CHECK(got.errors[0].run == 6);
    CHECK(got.errors[0].message == "run 6 fails");
  }
}

TEST_CASE("mpi: misuse throws on every rank, never hangs", "[ensemble][mpi]") {
  CHECK_THAT(g_before_init, TUMBLE_CONTAINS("MPI is not initialized"));
  const Tumbling t;
  const auto initial = [&](std::size_t i) { return t.initial(i); };
  const tumble::MpiEnsemble ensemble(t.scene, make, {.threads = 1});
  const std::vector<double> backwards{4.0, 2.0};
  CHECK_THROWS_AS(ensemble.integrate<Final>(3, initial, 0.0, backwards, t.observer()),
                  std::invalid_argument);
  CHECK_THROWS_AS(ensemble.fold<Final>(3, initial, 0.0, kTimes, t.observer(), 0.0, add, 0),
                  std::invalid_argument);
  // Each rank asks for another run count: every rank throws, and the next call still works.
  const auto runs = static_cast<std::size_t>(3 + rank());
  if (ensemble.ranks() > 1) {
    CHECK_THROWS_WITH(ensemble.integrate<Final>(runs, initial, 0.0, kTimes, t.observer()),
                      TUMBLE_CONTAINS("different run counts"));
  }
  const auto after = ensemble.integrate<Final>(2, initial, 0.0, kTimes, t.observer());
  CHECK(after.size() == (ensemble.rank() == 0 ? 2u : 0u));
}

int main(int argc, char** argv) {
  {
    const Tumbling t;
    try {
      const tumble::MpiEnsemble early(t.scene, make);
    } catch (const std::logic_error& e) {
      g_before_init = e.what();
    }
  }
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  if (provided < MPI_THREAD_FUNNELED) {
    std::fprintf(stderr, "this MPI does not provide MPI_THREAD_FUNNELED\n");
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  int status = 0;
  {
    Catch::Session session;
    status = session.applyCommandLine(argc, argv);
    if (status == 0) {
      status = session.run();
    }
  }
  // One failing rank fails the whole run (mpirun returns the first non-zero status).
  MPI_Finalize();
  return status;
}
