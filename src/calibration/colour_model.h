#pragma once
// The interface every colour correction shares: a map from one RGB-like triple to another
// (a 3x3 matrix, a root-polynomial, a 3D LUT), its name and its parameters as JSON.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/geometry.h"

namespace inim {

// Any map of colour triples (a forward model to invert, a function to sample into a LUT).
using ColourFunction = std::function<Vec3d(const Vec3d&)>;

class ColourModel {
 public:
  virtual ~ColourModel() = default;
  virtual Vec3d apply(const Vec3d& source) const = 0;
  // Short identifier, also the "model" field of parameters().
  virtual std::string name() const = 0;
  // What it is, for reports ("3D LUT, 33 nodes per axis, tetrahedral"); its name by default.
  virtual std::string describe() const { return name(); }
  // Everything needed to reproduce apply(), for reports and later reloading.
  virtual nlohmann::json parameters() const = 0;
};

}  // namespace inim
