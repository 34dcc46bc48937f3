#pragma once
// A sequential lens: rotationally symmetric spherical, conic or even-asphere surfaces along the
// optical axis,
// one of them the aperture stop, traced with real rays in double precision.
//
// Lens coordinates (mm): the optical axis is z, the first surface's vertex (object side) is at
// z = 0 and light from the object travels toward +z. A radius is positive when its centre of
// curvature lies on the image side (+z) of the vertex. Each surface owns the medium that
// follows it (toward the image) and the distance to the next surface, as in the pbrt-v4 lens
// format ("after" convention). The sensor sits `sensorDistanceMm()` behind the last vertex.
// Air gaps have n = 1 exactly: lens prescriptions give glass indices relative to air.
#include <string>
#include <vector>

#include "camera/even_asphere.h"
#include "core/geometry.h"
#include "spectral/dispersion.h"

namespace inim {

using Vec2d = glm::dvec2;  // (a same-type alias may be redeclared elsewhere)

// The helium d line, where lens data (n_d, focal lengths) are quoted.
constexpr double kLensReferenceLambdaNm = 587.56;

// A ray in lens coordinates, double precision; d is a unit vector.
struct LensRay {
  Vec3d o{0.0};
  Vec3d d{0.0, 0.0, 1.0};
};

struct LensSurface {
  double radiusMm = 0.0;    // vertex radius of curvature; 0 = flat
  double conic = 0.0;       // k: sag z = c r^2 / (1 + sqrt(1 - (1 + k) c^2 r^2))
  std::vector<double> asphere;  // even-asphere terms a_i on r^(2i+2), mm^(-2i-1) (even_asphere.h)
  double thicknessMm = 0.0; // vertex distance to the next surface (the last: see LensSystem)
  double apertureMm = 0.0;  // clear aperture diameter
  bool isStop = false;      // the aperture stop (flat, no refraction)
  IorPtr medium;            // medium after the surface (toward the image); null = air
  std::string mediumName = "air";  // for reports: "air", a catalog name, "n_d 1.67", ...
  std::string source;       // where the surface was read: "line 7" / "surfaces[3]" (messages)

  double curvature() const { return radiusMm == 0.0 ? 0.0 : 1.0 / radiusMm; }
  double semiAperture() const { return 0.5 * apertureMm; }
  bool isAir() const { return medium == nullptr; }
  bool isAsphere() const { return !asphere.empty(); }
  EvenAsphere shape() const { return {curvature(), conic, &asphere}; }
};

// What a lens file says about its design beyond the surfaces, for reports.
struct LensDesignInfo {
  std::vector<double> wavelengthsNm;  // the design wavelengths (Zemax WAVM), in file order
  double primaryWavelengthNm = 0.0;   // 0: none given
  double entrancePupilMm = 0.0;       // Zemax ENPD, 0: not given
  double fNumber = 0.0;               // Zemax FNUM (image space), 0: not given
  std::vector<std::string> warnings;  // what the loader read only approximately, one line each
};

enum class TraceDirection { ObjectToImage, ImageToObject };

struct TraceOptions {
  bool apertures = true;  // clip by the clear apertures (vignetting); off for paraxial work
  bool fresnel = false;   // multiply the throughput by the Fresnel transmittance (unpolarised)
  // Only surfaces first..last (lens order, inclusive; last = -1: the last surface) are
  // crossed, in the direction's order. Used to image the stop into the pupils.
  int first = 0;
  int last = -1;
};

// Why a ray did not make it.
enum class TraceStatus { Ok, Missed, Aperture, TotalInternalReflection };
const char* traceStatusName(TraceStatus s);

// One refraction (or stop crossing) along a traced path, for tests and diagnostics.
struct SurfaceHit {
  int surface = -1;
  Point3d p{0.0};
  Vec3d normal{0.0};  // unit, facing the incoming ray
  Vec3d dIn{0.0}, dOut{0.0};
  double nIn = 1.0, nOut = 1.0;
};

struct TraceResult {
  TraceStatus status = TraceStatus::Ok;
  int surface = -1;            // the surface where it stopped, when not Ok
  double transmittance = 1.0;  // Fresnel product when TraceOptions::fresnel
  bool ok() const { return status == TraceStatus::Ok; }
};

class LensSystem {
 public:
  LensSystem() = default;
  // Surfaces in object-first order with "after" thicknesses. No validation here: loaders
  // call validate() with their file name.
  LensSystem(std::vector<LensSurface> surfaces, std::string name = "", std::string file = "");

  const std::vector<LensSurface>& surfaces() const { return surfaces_; }
  int surfaceCount() const { return int(surfaces_.size()); }
  const std::string& name() const { return name_; }
  const std::string& file() const { return file_; }
  const LensDesignInfo& design() const { return design_; }
  void setDesign(LensDesignInfo d) { design_ = std::move(d); }
  int stopIndex() const { return stop_; }  // -1 when there is none
  double vertexZ(int i) const { return z_[size_t(i)]; }
  double lastVertexZ() const { return z_.back(); }
  double lengthMm() const { return z_.back(); }  // first to last vertex

  // Sag of surface i at radial distance r (relative to its vertex); NaN beyond the conic.
  // Aspheric terms included.
  double sag(int i, double r) const;
  // Index after surface i (toward the image) and before it, at a wavelength.
  double indexAfter(int i, double lambdaNm) const;
  double indexBefore(int i, double lambdaNm) const { return i == 0 ? 1.0 : indexAfter(i - 1, lambdaNm); }
  // True when any glass is dispersive (rays then depend on the wavelength).
  bool isDispersive() const;

  // Sensor (image plane) distance behind the last vertex. Set by focusing.
  double sensorDistanceMm() const { return sensorDistance_; }
  void setSensorDistanceMm(double d) { sensorDistance_ = d; }
  double sensorZ() const { return z_.back() + sensorDistance_; }

  // Aperture stop diameter; the design value is kept for reference (maximum aperture).
  double stopDiameterMm() const;
  double designStopDiameterMm() const { return designStopDiameter_; }
  void setStopDiameterMm(double d);

  // Real ray trace through every surface in `dir` order. On success `r` is the ray leaving the
  // last surface crossed (origin on it). With `path`, every crossing is appended to it.
  TraceResult trace(LensRay& r, double lambdaNm, TraceDirection dir, const TraceOptions& opt = {},
                    std::vector<SurfaceHit>* path = nullptr) const;
  // The same with the indices after each surface already evaluated (nAfter[i], size n).
  TraceResult traceWithIndices(LensRay& r, const double* nAfter, TraceDirection dir,
                               const TraceOptions& opt = {}, std::vector<SurfaceHit>* path = nullptr) const;
  // Indices after each surface at a wavelength (1 for air).
  std::vector<double> indicesAt(double lambdaNm) const;

  // Throws InputError (naming file_ and the surface's source) for: no or several stops, an
  // aperture <= 0, a negative thickness, a glass of zero thickness, a radius smaller than the
  // semi-aperture (or a conic undefined there), surfaces that cross inside their apertures,
  // a lens no near-axis ray passes, and a stop that the axial beam cannot fill because a
  // neighbouring aperture clips it first.
  void validate() const;

 private:
  void rebuild();
  // validate's steps (lens_system.cpp).
  void validateSurfaces() const;
  void validateAsphere(int surface) const;
  void validateSpacing() const;
  double validateNearAxisRay() const;
  void validateStopFill(double nearAxisHeightMm) const;
  [[noreturn]] void fail(int surface, const std::string& column, const std::string& value,
                         const std::string& expected) const;
  std::vector<LensSurface> surfaces_;
  std::vector<double> z_;  // vertex positions
  std::vector<double> curvature_;  // LensSurface::curvature(), once: a division per surface and ray
  std::string name_, file_;
  LensDesignInfo design_;
  int stop_ = -1;
  double sensorDistance_ = 0.0;
  double designStopDiameter_ = 0.0;
};

// Intersection of a ray with the conic surface of curvature c and conic k whose vertex is at
// the origin (sag branch through the vertex). Returns the smallest t > tMin or -1.
double intersectConic(const Vec3d& o, const Vec3d& d, double c, double k, double tMin = 1e-9);
// Unit normal of that surface at p, pointing toward -z at the vertex.
Vec3d conicNormal(const Vec3d& p, double c, double k);
// Vector Snell refraction of unit d at unit normal n (any side) from n1 into n2. Returns false
// on total internal reflection.
bool snellRefract(const Vec3d& d, const Vec3d& n, double n1, double n2, Vec3d& out);
// Unpolarised Fresnel transmittance for a dielectric interface at incidence cosine cosI.
double fresnelTransmittance(double cosI, double n1, double n2);

}  // namespace inim
