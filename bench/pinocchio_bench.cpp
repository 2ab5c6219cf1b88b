// Per-call timing of Pinocchio's core algorithms on a fixed-base URDF, for the side-by-side
// comparison with `screwdyn bench` (bench/compare.sh). Written for screwdyn; the measurement
// protocol is the same as screwdyn-cli's `bench` command:
//
//   * states: q uniform within the position limits (an infinite limit is clamped to ±π),
//     v, a and τ uniform in [-1, 1]; NSTATES states drawn once before timing;
//   * one batch = CALLS calls cycling through the states, timed as a whole with a monotonic
//     clock; ns per call = elapsed / CALLS;
//   * the reported figure is the median over BATCHES batches (after one warm-up batch).
//
// Usage: pinocchio_bench MODEL.txt [BATCHES] [CALLS]   → one JSON line on stdout:
//   {"model": "...", "nq": n, "ns_per_call": {"fk": ..., "jacobians": ..., ...}}
//
// MODEL.txt is the URDF's joint tree as written by bench/export_model.py (Pinocchio's own URDF
// parser, run from Python); the model is rebuilt here with Model::addJoint. Pinocchio's
// algorithms are compiled from its headers (inline templates, no
// PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION), so they get the same -O3 and CPU flags as this file,
// and nothing is linked from the wheel's compiled libraries.

#include <pinocchio/multibody.hpp>

#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/jacobian.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/rnea-derivatives.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
  // Rebuilds the model written by export_model.py.
  pinocchio::Model load(const std::string & path)
  {
    std::ifstream in(path);
    if (!in)
      throw std::runtime_error("cannot read " + path);
    pinocchio::Model model;
    std::getline(in, model.name);
    std::string line;
    std::vector<std::pair<double, double>> limits;
    while (std::getline(in, line))
    {
      if (line.empty())
        continue;
      std::istringstream ss(line);
      std::string kind;
      double v[31];
      ss >> kind;
      for (double & x : v)
        ss >> x;
      if (!ss)
        throw std::runtime_error("bad line in " + path + ": " + line);
      const auto parent = static_cast<pinocchio::JointIndex>(v[0]);
      Eigen::Matrix3d r, ic;
      for (int k = 0; k < 9; ++k)
      {
        r(k / 3, k % 3) = v[4 + k];
        ic(k / 3, k % 3) = v[17 + k];
      }
      const pinocchio::SE3 placement(r, Eigen::Vector3d(v[1], v[2], v[3]));
      const pinocchio::Inertia inertia(v[13], Eigen::Vector3d(v[14], v[15], v[16]), ic);
      const Eigen::Vector3d axis(v[26], v[27], v[28]);
      pinocchio::JointModel joint;
      if (kind == "JointModelRX")
        joint = pinocchio::JointModelRX();
      else if (kind == "JointModelRY")
        joint = pinocchio::JointModelRY();
      else if (kind == "JointModelRZ")
        joint = pinocchio::JointModelRZ();
      else if (kind == "JointModelPX")
        joint = pinocchio::JointModelPX();
      else if (kind == "JointModelPY")
        joint = pinocchio::JointModelPY();
      else if (kind == "JointModelPZ")
        joint = pinocchio::JointModelPZ();
      else if (kind == "JointModelRevoluteUnaligned")
        joint = pinocchio::JointModelRevoluteUnaligned(axis);
      else if (kind == "JointModelPrismaticUnaligned")
        joint = pinocchio::JointModelPrismaticUnaligned(axis);
      else
        throw std::runtime_error("unsupported joint type " + kind);
      const auto id =
        model.addJoint(parent, joint, placement, "joint" + std::to_string(model.njoints));
      model.appendBodyToJoint(id, inertia, pinocchio::SE3::Identity());
      limits.emplace_back(v[29], v[30]);
    }
    for (size_t i = 0; i < limits.size(); ++i)
    {
      model.lowerPositionLimit[i] = limits[i].first;
      model.upperPositionLimit[i] = limits[i].second;
    }
    return model;
  }

  // Keeps the optimiser from dropping a computed result.
  template<typename T>
  inline void keep(const T & x)
  {
    asm volatile("" : : "g"(&x) : "memory");
  }

  double median(std::vector<double> xs)
  {
    std::sort(xs.begin(), xs.end());
    const size_t n = xs.size();
    return n % 2 ? xs[n / 2] : 0.5 * (xs[n / 2 - 1] + xs[n / 2]);
  }

  // Median ns per call of `call(k)` over `batches` batches of `calls` calls each.
  template<typename F>
  double time_it(int batches, int calls, int nstates, F && call)
  {
    std::vector<double> per_call;
    for (int b = -1; b < batches; ++b)
    {
      const auto t0 = std::chrono::steady_clock::now();
      for (int c = 0; c < calls; ++c)
        call(c % nstates);
      const auto t1 = std::chrono::steady_clock::now();
      if (b >= 0)
        per_call.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / calls);
    }
    return median(per_call);
  }
} // namespace

int main(int argc, char ** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s MODEL.txt [BATCHES] [CALLS]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int batches = argc > 2 ? std::atoi(argv[2]) : 21;
  const int calls = argc > 3 ? std::atoi(argv[3]) : 20000;
  const int nstates = 1000;

  const pinocchio::Model model = load(path); // fixed base
  pinocchio::Data data(model);
  const int n = model.nq;

  // Random states, uniform within the limits (see the header).
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), u01(0.0, 1.0);
  std::vector<Eigen::VectorXd> qs, vs, as, taus;
  for (int k = 0; k < nstates; ++k)
  {
    Eigen::VectorXd q(n), v(n), a(n), tau(n);
    for (int i = 0; i < n; ++i)
    {
      double lo = model.lowerPositionLimit[i], hi = model.upperPositionLimit[i];
      if (!std::isfinite(lo) || lo < -M_PI)
        lo = -M_PI;
      if (!std::isfinite(hi) || hi > M_PI)
        hi = M_PI;
      q[i] = lo + (hi - lo) * u01(rng);
      v[i] = unit(rng);
      a[i] = unit(rng);
      tau[i] = unit(rng);
    }
    qs.push_back(q);
    vs.push_back(v);
    as.push_back(a);
    taus.push_back(tau);
  }

  const double fk = time_it(batches, calls, nstates, [&](int k) {
    pinocchio::forwardKinematics(model, data, qs[k]);
    keep(data.oMi.back());
  });
  const double jac = time_it(batches, calls, nstates, [&](int k) {
    pinocchio::computeJointJacobians(model, data, qs[k]);
    keep(data.J);
  });
  const double rnea = time_it(batches, calls, nstates, [&](int k) {
    keep(pinocchio::rnea(model, data, qs[k], vs[k], as[k]));
  });
  // Pinocchio's crba fills the upper triangle only.
  const double crba = time_it(batches, calls, nstates, [&](int k) {
    keep(pinocchio::crba(model, data, qs[k]));
  });
  const double aba = time_it(batches, calls, nstates, [&](int k) {
    keep(pinocchio::aba(model, data, qs[k], vs[k], taus[k]));
  });

  // Derivatives (issue 15): the data.dtau_dq / dtau_dv (M in data.M, upper triangle) and
  // data.ddq_dq / ddq_dv / Minv outputs, no external forces.
  const double rnea_derivatives = time_it(batches, calls, nstates, [&](int k) {
    pinocchio::computeRNEADerivatives(model, data, qs[k], vs[k], as[k]);
    keep(data.dtau_dq);
  });
  const double aba_derivatives = time_it(batches, calls, nstates, [&](int k) {
    pinocchio::computeABADerivatives(model, data, qs[k], vs[k], taus[k]);
    keep(data.ddq_dq);
  });

  std::printf(
    "{\"model\": \"%s\", \"nq\": %d, \"ns_per_call\": {\"fk\": %.2f, \"jacobians\": %.2f, "
    "\"rnea\": %.2f, \"crba\": %.2f, \"aba\": %.2f, \"rnea_derivatives\": %.2f, "
    "\"aba_derivatives\": %.2f}}\n",
    model.name.c_str(), n, fk, jac, rnea, crba, aba, rnea_derivatives, aba_derivatives);
  return 0;
}
