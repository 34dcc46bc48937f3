// Inversion of a forward function into a 3D LUT (declared in lut3d.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "calibration/colour_models.h"
#include "calibration/lut3d.h"
#include "core/error.h"
#include "core/parallel.h"

namespace inim {
namespace {

Vec3d clampToBounds(const Vec3d& x, const InversionSettings& s) {
  return glm::clamp(x, Vec3d(s.lowerBound), Vec3d(s.upperBound));
}

Vec3d evaluate(const ColourFunction& forward, const Vec3d& drive) {
  const Vec3d v = forward(drive);
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw InputError("", "forward", "F(" + std::to_string(drive.x) + ", " + std::to_string(drive.y) + ", " +
                                        std::to_string(drive.z) + ")",
                     "finite values everywhere on the drive domain");
  return v;
}

// Columns dF/dx_i by central differences, one-sided at the domain's edges (F is never called
// outside the bounds).
glm::dmat3 jacobian(const ColourFunction& forward, const Vec3d& x, const InversionSettings& s) {
  glm::dmat3 j(0.0);
  for (int i = 0; i < 3; ++i) {
    Vec3d lo = x, hi = x;
    lo[i] = std::max(s.lowerBound, x[i] - s.jacobianStep);
    hi[i] = std::min(s.upperBound, x[i] + s.jacobianStep);
    j[i] = (evaluate(forward, hi) - evaluate(forward, lo)) / (hi[i] - lo[i]);
  }
  return j;
}

// The Gauss-Newton step for the variables not held at a bound: a variable at 0 whose descent
// direction points below 0 (or at 1 and above 1) is fixed for this step.
Vec3d boundedGaussNewtonStep(const glm::dmat3& j, const Vec3d& x, const Vec3d& residual, const InversionSettings& s) {
  const Vec3d descent = glm::transpose(j) * residual;
  glm::dmat3 normal = glm::transpose(j) * j;
  Vec3d rhs = descent;
  const double damping = 1e-12 * (normal[0][0] + normal[1][1] + normal[2][2]) + 1e-300;
  for (int i = 0; i < 3; ++i) {
    const bool held = (x[i] <= s.lowerBound && descent[i] < 0.0) || (x[i] >= s.upperBound && descent[i] > 0.0);
    if (held) {
      for (int k = 0; k < 3; ++k) normal[i][k] = normal[k][i] = 0.0;
      normal[i][i] = 1.0;
      rhs[i] = 0.0;
    } else {
      normal[i][i] += damping;
    }
  }
  return glm::inverse(normal) * rhs;
}

struct NodeSolution {
  Vec3d drive;
  double residual;
};

NodeSolution solveNode(const ColourFunction& forward, const Vec3d& target, const Vec3d& guess,
                       const InversionSettings& settings) {
  Vec3d x = clampToBounds(guess, settings);
  Vec3d residual = target - evaluate(forward, x);
  double error = glm::length(residual);
  for (int iteration = 0; iteration < settings.maxIterations && error > settings.tolerance; ++iteration) {
    const Vec3d step = boundedGaussNewtonStep(jacobian(forward, x, settings), x, residual, settings);
    bool accepted = false;
    // Damping by halving until the residual decreases (the projection can spoil a full step).
    for (double scale = 1.0; scale > 1e-6 && !accepted; scale *= 0.5) {
      const Vec3d trial = clampToBounds(x + scale * step, settings);
      const Vec3d trialResidual = target - evaluate(forward, trial);
      if (glm::length(trialResidual) < error) {
        x = trial, residual = trialResidual, error = glm::length(trialResidual);
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  return {x, error};
}

// A 3x3 matrix mapping F's values back to drives, fitted on a coarse grid: the starting guess.
MatrixModel initialGuessModel(const ColourFunction& forward, int samplesPerAxis) {
  ColourPairs pairs;
  const int n = std::max(2, samplesPerAxis);
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const Vec3d drive = Vec3d(r, g, b) / double(n - 1);
        pairs.sources.push_back(evaluate(forward, drive));
        pairs.targets.push_back(drive);
      }
  return MatrixModel::fit(pairs);
}

}  // namespace

InverseLut invertToLut(const ColourFunction& forward, const InversionSettings& settings) {
  InverseLut out{Lut3d(settings.size), {}, 0.0, 0};
  const MatrixModel guess = initialGuessModel(forward, settings.guessSamplesPerAxis);
  const int n = settings.size;
  out.residuals.assign(size_t(n) * n * n, 0.0);
  std::vector<Vec3d> drives(out.residuals.size());
  // Each node is solved independently; F must be safe to call from several threads.
  parallelForRange(int64_t(drives.size()), [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const Vec3d target = out.lut.node(int(i % n), int(i / n % n), int(i / (int64_t(n) * n)));
      const NodeSolution s = solveNode(forward, target, guess.apply(target), settings);
      drives[i] = s.drive;
      out.residuals[i] = s.residual;
    }
  }, nullptr, 64);
  for (size_t i = 0; i < drives.size(); ++i) {
    out.lut.set(int(i % n), int(i / n % n), int(i / (size_t(n) * n)), drives[i]);
    out.maxResidual = std::max(out.maxResidual, out.residuals[i]);
    if (out.residuals[i] > settings.reachedTolerance) ++out.unreachedCount;
  }
  return out;
}

}  // namespace inim
