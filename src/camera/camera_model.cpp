#include "core/format.h"
#include "camera/camera_model.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/sampling.h"
#include "spectral/sampled.h"

namespace inim {

namespace {


std::string vecText(const Vec3d& v) { return "[" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + "]"; }

// Inverse of sampleUniformDiskConcentric (Shirley-Chiu): unit disk -> [0, 1)^2.
Vec2d inverseConcentric(const Vec2d& d) {
  const double r = std::sqrt(d.x * d.x + d.y * d.y);
  if (r == 0.0) return Vec2d(0.5);
  const double q = 3.14159265358979323846 / 4.0;
  double phi = std::atan2(d.y, d.x);
  Vec2d o;
  if (phi >= -q && phi <= q) {
    o = Vec2d(r, r * phi / q);
  } else if (phi > q && phi <= 3.0 * q) {
    o = Vec2d(r * (2.0 * q - phi) / q, r);
  } else if (phi < -q && phi >= -3.0 * q) {
    const double t = phi + 3.14159265358979323846;  // in [pi/4, 3pi/4]
    o = Vec2d(-r * (2.0 * q - t) / q, -r);
  } else {
    const double t = phi > 0.0 ? phi - 3.14159265358979323846 : phi + 3.14159265358979323846;  // in [-pi/4, pi/4]
    o = Vec2d(-r, -r * t / q);
  }
  return 0.5 * (o + Vec2d(1.0));
}

}  // namespace

const char* cameraModelName(CameraModelKind k) {
  switch (k) {
    case CameraModelKind::Pinhole: return "pinhole";
    case CameraModelKind::ThinLens: return "thin-lens";
    case CameraModelKind::RealLens: return "real-lens";
  }
  return "?";
}

// ---------------------------------------------------------------------------------------------
// CameraModel

CameraModel::CameraModel(const SensorGeometry& sensor, const ViewingPose& pose) : sensor_(sensor), pose_(pose) {
  if (sensor.widthPx < 1 || sensor.heightPx < 1 || !(sensor.pitchMm > 0.0))
    throw InputError("", "sensor", std::to_string(sensor.widthPx) + " x " + std::to_string(sensor.heightPx) + " px, pitch " +
                         formatNumber(sensor.pitchMm) + " mm", "a sensor of at least 1 x 1 pixels with a pitch > 0");
  setPose(pose);
}

void CameraModel::setPose(const ViewingPose& pose) {
  pose_ = pose;
  const Vec3d look = pose.lookAt - pose.eye;
  const double len = glm::length(look);
  if (!(len > 0.0) || !std::isfinite(len))
    throw InputError("", "pose", "eye " + vecText(pose.eye) + ", look_at " + vecText(pose.lookAt),
                     "an eye position different from the look-at point");
  back_ = -look / len;
  Vec3d r = glm::cross(pose.up, back_);
  const double rl = glm::length(r);
  if (!(rl > 1e-9 * std::max(1.0, glm::length(pose.up))) || !std::isfinite(rl))
    throw InputError("", "pose.up", vecText(pose.up), "an up vector not parallel to the viewing direction");
  right_ = r / rl;
  up_ = glm::cross(back_, right_);
}

std::unique_ptr<RealLensCameraModel> RealLensCameraModel::atPose(const ViewingPose& pose) const {
  auto m = std::make_unique<RealLensCameraModel>(*this);
  m->setPose(pose);
  return m;
}

std::unique_ptr<CameraModel> CameraModel::sameLensAt(const ViewingPose&, const SensorGeometry&,
                                                    const RealLensSettings&) const {
  return nullptr;
}

std::unique_ptr<CameraModel> RealLensCameraModel::sameLensAt(const ViewingPose& pose, const SensorGeometry& sensor,
                                                            const RealLensSettings& s) const {
  const SensorGeometry& mine = this->sensor();
  if (mine.widthPx != sensor.widthPx || mine.heightPx != sensor.heightPx || mine.pitchMm != sensor.pitchMm ||
      settings_.fNumber != s.fNumber || settings_.focusDistanceMm != s.focusDistanceMm ||
      settings_.focusMode != s.focusMode || settings_.fresnel != s.fresnel)
    return nullptr;
  return atPose(pose);
}

float CameraModel::generateRay(int col, int row, Rng& rng, float lambdaNm, Ray& out) const {
  const float jx = rng.uniform(), jy = rng.uniform();
  const float u = rng.uniform(), v = rng.uniform();
  return generateRay(Vec2(float(col) + jx, float(row) + jy), Vec2(u, v), lambdaNm, out);
}

bool CameraModel::apertureDomain(Vec2, Vec2d& lo, Vec2d& hi) const {
  lo = Vec2d(0.0);
  hi = Vec2d(1.0);
  return true;
}

float CameraModel::apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const {
  if (!(a.x >= 0.0 && a.y >= 0.0 && a.x < 1.0 && a.y < 1.0)) return 0.0f;
  return generateRay(pixel, Vec2(float(a.x), float(a.y)), lambdaNm, out);
}

Vec2d CameraModel::uprightSensorOffset(Vec2 pixel) const {
  return {(double(pixel.x) - 0.5 * sensor_.widthPx) * sensor_.pitchMm,
          -(double(pixel.y) - 0.5 * sensor_.heightPx) * sensor_.pitchMm};
}

void CameraModel::setRay(const Point3d& o, const Vec3d& d, Ray& out) {
  out.o = Point3(o);
  out.d = Vec3(glm::normalize(d));
  out.tMin = 0.0f;
  out.tMax = kInfinity;
}

// ---------------------------------------------------------------------------------------------
// Pinhole

PinholeCameraModel::PinholeCameraModel(const SensorGeometry& sensor, const ViewingPose& pose, double imageDistanceMm,
                                       bool naturalVignetting)
    : CameraModel(sensor, pose), d_(imageDistanceMm), vignetting_(naturalVignetting) {
  if (!(d_ > 0.0) || !std::isfinite(d_))
    throw InputError("", "image_distance_mm", formatNumber(d_), "a pinhole-to-sensor distance > 0");
}

float PinholeCameraModel::generateRay(Vec2 pixel, Vec2, float, Ray& out) const {
  const Vec2d s = uprightSensorOffset(pixel);
  const Vec3d dl(s.x, s.y, -d_);
  const double cosT = d_ / glm::length(dl);
  setRay(pose_.eye, toWorldDir(dl), out);
  return vignetting_ ? float(cosT * cosT * cosT * cosT) : 1.0f;
}

std::string PinholeCameraModel::describe() const {
  return "pinhole camera, image distance " + formatNumber(d_) + " mm, horizontal FOV " + formatNumber(horizontalFovDeg()) + " deg";
}

double PinholeCameraModel::horizontalFovDeg() const {
  return 2.0 * std::atan(0.5 * sensor_.widthMm() / d_) * 180.0 / kPiD;
}

// ---------------------------------------------------------------------------------------------
// Thin lens

ThinLensCameraModel::ThinLensCameraModel(const SensorGeometry& sensor, const ViewingPose& pose, double f, double N,
                                         double s, bool naturalVignetting)
    : CameraModel(sensor, pose), f_(f), n_(N), s_(s), vignetting_(naturalVignetting) {
  if (!(f > 0.0) || !std::isfinite(f)) throw InputError("", "focal_length_mm", formatNumber(f), "a focal length > 0");
  if (!(N > 0.0) || !std::isfinite(N)) throw InputError("", "f_number", formatNumber(N), "an f-number > 0");
  if (s_ <= 0.0) s_ = glm::length(pose.lookAt - pose.eye);
  if (!(s_ > f)) throw InputError("", "focus_distance_mm", formatNumber(s_), "a focus distance > the focal length " + formatNumber(f));
  sPrime_ = std::isinf(s_) ? f : f * s_ / (s_ - f);
  aperture_ = 0.5 * f / N;
}

float ThinLensCameraModel::generateRay(Vec2 pixel, Vec2 uLens, float, Ray& out) const {
  const Vec2d s = uprightSensorOffset(pixel);
  const Vec3d chief(s.x, s.y, -sPrime_);  // direction through the lens centre
  const double cosT = sPrime_ / glm::length(chief);
  const Vec2 disk = sampleUniformDiskConcentric(uLens);
  const Vec3d lensPt(aperture_ * disk.x, aperture_ * disk.y, 0.0);
  Vec3d dir;
  if (std::isinf(s_)) {
    dir = chief;
  } else {
    const Vec3d focusPt = chief * (s_ / sPrime_);  // on the plane of focus, z = -s
    dir = focusPt - lensPt;
  }
  setRay(toWorld(lensPt), toWorldDir(dir), out);
  return vignetting_ ? float(cosT * cosT * cosT * cosT) : 1.0f;
}

bool ThinLensCameraModel::apertureDomain(Vec2, Vec2d& lo, Vec2d& hi) const {
  lo = Vec2d(-1.0);
  hi = Vec2d(1.0);
  return true;
}

float ThinLensCameraModel::apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const {
  if (!(a.x * a.x + a.y * a.y <= 1.0)) return 0.0f;
  const Vec2d u = glm::clamp(inverseConcentric(a), Vec2d(0.0), Vec2d(0x1.fffffep-1));
  return generateRay(pixel, Vec2(float(u.x), float(u.y)), lambdaNm, out) / float(3.14159265358979323846);
}

std::string ThinLensCameraModel::describe() const {
  return "thin-lens camera, f " + formatNumber(f_) + " mm, f/" + formatNumber(n_) + ", focused at " + formatNumber(s_) + " mm (sensor at " +
         formatNumber(sPrime_) + " mm), horizontal FOV " + formatNumber(horizontalFovDeg()) + " deg";
}

double ThinLensCameraModel::horizontalFovDeg() const {
  return 2.0 * std::atan(0.5 * sensor_.widthMm() / sPrime_) * 180.0 / kPiD;
}

// ---------------------------------------------------------------------------------------------
// Real lens

RealLensCameraModel::RealLensCameraModel(LensSystem lens, const SensorGeometry& sensor, const ViewingPose& pose,
                                         const Settings& settings)
    : CameraModel(sensor, pose), lens_(std::move(lens)), settings_(settings) {
  const double lambda = settings.focusWavelengthNm;
  if (settings.fNumber > 0.0) setFNumber(lens_, settings.fNumber, lambda);
  info_ = analyzeLens(lens_, lambda);
  focus_ = settings.focusDistanceMm > 0.0 ? settings.focusDistanceMm : glm::length(pose.lookAt - pose.eye);
  // The object plane, in lens coordinates; it must lie in front of the first surface.
  const double zEP = info_.entrancePupil.positionMm;
  const double objectZ = std::isinf(focus_) ? -std::numeric_limits<double>::infinity() : zEP - focus_;
  const double frontZ = std::min(0.0, lens_.sag(0, lens_.surfaces().front().semiAperture()));
  if (!(objectZ < frontZ))
    throw InputError(lens_.file(), "focus_distance_mm", formatNumber(focus_),
                     "a focus distance beyond the front of the lens (> " + formatNumber(zEP - frontZ) +
                         " mm from the entrance pupil)");
  const double d = focusSensorDistance(lens_, objectZ, settings.focusMode, lambda);
  const double rear = std::max(0.0, lens_.sag(lens_.surfaceCount() - 1, lens_.surfaces().back().semiAperture()));
  if (!(d > rear) || !std::isfinite(d))
    throw InputError(lens_.file(), "focus_distance_mm", formatNumber(focus_),
                     "a focus distance the lens can reach (the sensor would sit " + formatNumber(d) +
                         " mm behind the last vertex)");
  lens_.setSensorDistanceMm(d);
  indices550_ = lens_.indicesAt(550.0);

  ExitPupilBounds::Settings ps = settings.pupil;
  if (ps.wavelengthsNm.empty()) {
    ps.wavelengthsNm = {lambda};
    if (lens_.isDispersive()) ps.wavelengthsNm = {double(kLambdaMin), lambda, double(kLambdaMax)};
  }
  bounds_ = ExitPupilBounds::shared(lens_, sensor.halfDiagonalMm() * 1.0001, ps);

  // Centre irradiance per unit radiance: E = integral over the rear plane of cos^4 / z^2.
  e0_ = 0.0;
  const PupilBox& b = bounds_->box(0.0);
  if (!b.empty) {
    const int n = 160;
    const Vec2d cell = (b.hi - b.lo) / double(n);
    double sum = 0.0;
    LensRay lr;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Point3d q(b.lo.x + (i + 0.5) * cell.x, b.lo.y + (j + 0.5) * cell.y, bounds_->rearZ());
        sum += traceFromSensor({0.0, 0.0}, q, lambda, lr);
      }
    const double z = lens_.sensorZ() - bounds_->rearZ();
    e0_ = sum * cell.x * cell.y / (z * z);
  }
  if (!(e0_ > 0.0))
    throw InputError(lens_.file(), "aperture", "no ray reaches the image centre", "a lens that passes light to the sensor centre");
}

Vec2d RealLensCameraModel::sensorPoint(Vec2 pixel) const {
  const Vec2d u = uprightSensorOffset(pixel);
  return -u;  // the lens inverts the image
}

double RealLensCameraModel::traceFromSensor(const Vec2d& s, const Point3d& rearPoint, double lambdaNm,
                                            LensRay& r) const {
  const Point3d film(s.x, s.y, lens_.sensorZ());
  r.o = film;
  r.d = glm::normalize(rearPoint - film);
  const double cosT = -r.d.z;
  if (!(cosT > 0.0)) return 0.0;
  TraceOptions opt;
  opt.fresnel = settings_.fresnel;
  TraceResult tr = lambdaNm == 550.0 && !indices550_.empty()
                       ? lens_.traceWithIndices(r, indices550_.data(), TraceDirection::ImageToObject, opt)
                       : lens_.trace(r, lambdaNm, TraceDirection::ImageToObject, opt);
  if (!tr.ok()) return 0.0;
  const double c2 = cosT * cosT;
  return c2 * c2 * tr.transmittance;
}

double RealLensCameraModel::sampleLensRay(const Vec2d& s, Vec2 uLens, double lambdaNm, LensRay& r) const {
  Point3d q;
  double pdf = 0.0;
  if (!bounds_->sample(s, uLens, q, pdf)) return 0.0;
  const double w = traceFromSensor(s, q, lambdaNm, r);
  if (w == 0.0) return 0.0;
  const double z = lens_.sensorZ() - bounds_->rearZ();
  return w / (z * z * pdf);
}

Ray RealLensCameraModel::lensToWorld(const LensRay& r) const {
  const double zEP = info_.entrancePupil.positionMm;
  Ray out;
  setRay(toWorld(Vec3d(r.o.x, r.o.y, r.o.z - zEP)), toWorldDir(r.d), out);
  return out;
}

float RealLensCameraModel::generateRay(Vec2 pixel, Vec2 uLens, float lambdaNm, Ray& out) const {
  LensRay r;
  const double w = sampleLensRay(sensorPoint(pixel), uLens, lambdaNm, r);
  if (w == 0.0) return 0.0f;
  out = lensToWorld(r);
  return float(w / e0_);
}

// The exit-pupil box of the pixel's radius, rotated to the pixel's azimuth, grown by 5%.
bool RealLensCameraModel::apertureDomain(Vec2 pixel, Vec2d& lo, Vec2d& hi) const {
  const Vec2d s = sensorPoint(pixel);
  const double r = std::sqrt(s.x * s.x + s.y * s.y);
  const PupilBox& b = bounds_->box(r);
  if (b.empty) return false;
  const double c = r > 0.0 ? s.x / r : 1.0, sn = r > 0.0 ? s.y / r : 0.0;
  lo = Vec2d(1e300);
  hi = Vec2d(-1e300);
  for (int i = 0; i < 4; ++i) {
    const Vec2d q((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y);
    const Vec2d p(c * q.x - sn * q.y, sn * q.x + c * q.y);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec2d m = 0.05 * (hi - lo);
  lo -= m;
  hi += m;
  return true;
}

// traceFromSensor's weight / (z^2 E0), z the sensor's distance from the rear-vertex plane:
// irradiance per unit radiance per mm^2 of that plane, normalised like generateRay.
float RealLensCameraModel::apertureRay(Vec2 pixel, const Vec2d& a, float lambdaNm, Ray& out) const {
  LensRay lr;
  const double w = traceFromSensor(sensorPoint(pixel), Point3d(a.x, a.y, bounds_->rearZ()), lambdaNm, lr);
  if (!(w > 0.0)) return 0.0f;
  out = lensToWorld(lr);
  const double z = lens_.sensorZ() - bounds_->rearZ();
  return float(w * (1.0 / (z * z * e0_)));
}

std::string RealLensCameraModel::describe() const {
  std::ostringstream o;
  o << "real-lens camera: " << (lens_.name().empty() ? lens_.file() : lens_.name()) << ", EFL " << formatNumber(info_.eflMm)
    << " mm, f/" << formatNumber(info_.fNumber) << ", focused (" << focusModeName(settings_.focusMode) << ") at "
    << formatNumber(focus_) << " mm from the entrance pupil, sensor " << formatNumber(sensorDistanceMm())
    << " mm behind the last vertex, horizontal FOV " << formatNumber(horizontalFovDeg()) << " deg";
  return o.str();
}

double RealLensCameraModel::horizontalFovDeg() const {
  // Chief ray from the sensor's edge through the centre of the exit pupil.
  const Vec2d s(0.5 * sensor_.widthMm(), 0.0);
  const Point3d film(s.x, s.y, lens_.sensorZ());
  const Point3d xp(0.0, 0.0, lens_.lastVertexZ() + info_.exitPupil.positionMm);
  LensRay r{film, glm::normalize(xp - film)};
  TraceOptions opt;
  opt.apertures = false;
  if (lens_.trace(r, settings_.focusWavelengthNm, TraceDirection::ImageToObject, opt).ok() && r.d.z < 0.0)
    return 2.0 * std::atan(std::sqrt(r.d.x * r.d.x + r.d.y * r.d.y) / -r.d.z) * 180.0 / kPiD;
  return 2.0 * std::atan(0.5 * sensor_.widthMm() / info_.eflMm) * 180.0 / kPiD;
}

}  // namespace inim
