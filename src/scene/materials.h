#pragma once
// Surface materials and their scattering functions (all in a local shading frame where the
// normal is +z, pbrt-v4 conventions: wo and wi point away from the surface).
//
//  diffuse     Lambertian reflectance from a texture (spectrum, RGB image or printed pattern)
//  dielectric  smooth interface with n(lambda) (catalog name or constant); Fresnel reflect /
//              refract, TIR; optional Beer-Lambert absorption inside. A dispersive index
//              terminates the secondary wavelengths on refraction.
//  thin        (dielectric with "thin": true) a thin sheet, e.g. a gel filter: light goes
//              straight through (no bending) with the sheet's multiple-reflection Fresnel
//              R/T and its internal transmittance tau(lambda) per pass
//  conductor   metal with complex index eta + i k (catalog name or spectra); smooth mirror or
//              GGX (Trowbridge-Reitz) microfacets with roughness alpha
//  emitter     black surface that emits; any material may also carry "emission"
#include <string>

#include "core/geometry.h"
#include "scene/texture.h"
#include "spectral/baked_spectrum.h"
#include "spectral/dispersion.h"

namespace inim {

enum class MaterialType { Diffuse, Dielectric, ThinDielectric, Conductor, Emitter };

struct Material {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  // diffuse
  ReflectanceTexture reflectance;
  // dielectric / thin
  IorPtr ior;             // as given (catalog or constant)
  BakedSpectrum n{1.5f};  // n(lambda), baked
  bool dispersive = false;
  bool absorbing = false;
  BakedSpectrum sigma;          // thick: absorption coefficient, 1/mm
  BakedSpectrum tau{1.0f};      // thin: internal transmittance per pass
  BakedSpectrum negLogTau{0.0f};  // thin: -ln(tau), for oblique paths tau^(1/cos)
  // conductor
  BakedSpectrum eta{1.0f}, k{0.0f};
  float alpha = 0.0f;  // GGX roughness; 0 = mirror
  // emission (radiance, already scaled)
  bool emissive = false;
  BakedSpectrum Le;
  bool twoSided = false;

  // True when the BSDF is a Dirac delta (no light sampling possible).
  bool isSpecular() const {
    return type == MaterialType::Dielectric || type == MaterialType::ThinDielectric ||
           (type == MaterialType::Conductor && alpha < 1e-3f);
  }
  bool isBlack() const { return type == MaterialType::Emitter; }
};

// ---- Fresnel and specular geometry ------------------------------------------------------

// Unpolarised Fresnel reflectance of a dielectric interface. eta = n_transmitted/n_incident
// for cosThetaI > 0; a negative cosThetaI means the ray arrives from the other side.
float fresnelDielectric(float cosThetaI, float eta);
// Unpolarised Fresnel reflectance of a conductor with complex index eta + i k (outside n = 1).
float fresnelConductor(float cosThetaI, float eta, float k);
// Refracts wi (pointing away from the surface) about n. eta = n_t/n_i relative to the side n
// points to. Returns false on total internal reflection; etap is the eta actually used.
bool refract(const Vec3& wi, Vec3 n, float eta, float* etap, Vec3* wt);
inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + 2.0f * glm::dot(wo, n) * n; }
// A thin sheet (two parallel interfaces, single-surface reflectance R, internal transmittance
// tau per pass) summed over all internal reflections.
void thinSheet(float R, float tau, float* Rtot, float* Ttot);

// ---- Trowbridge-Reitz (GGX) microfacets, isotropic, local frame (n = +z) -----------------
namespace ggx {
float D(const Vec3& wm, float alpha);
float lambda(const Vec3& w, float alpha);
float G1(const Vec3& w, float alpha);
float G(const Vec3& wo, const Vec3& wi, float alpha);
// Samples a visible normal for wo (Heitz 2018); wo.z > 0.
Vec3 sampleWm(const Vec3& wo, Vec2 u, float alpha);
// pdf of wi = reflect(wo, wm) when wm is sampled by sampleWm.
float pdfReflect(const Vec3& wo, const Vec3& wi, float alpha);
}  // namespace ggx

// Rough conductor BRDF value (local frame, both directions in the upper hemisphere).
SampledSpectrum roughConductorF(const Material& m, const Vec3& wo, const Vec3& wi,
                                const SampledWavelengths& lambda);
SampledSpectrum conductorFresnel(const Material& m, float cosThetaI,
                                 const SampledWavelengths& lambda);

}  // namespace inim
