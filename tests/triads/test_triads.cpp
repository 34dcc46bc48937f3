// Triads, the Zemax SDF source file, and EIA formation on a detector at the panel plane.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.h"
#include "display/display.h"
#include "fixtures.h"
#include "rays/pinhole_rays.h"
#include "triads/sdf.h"
#include "triads/triads.h"

namespace fs = std::filesystem;
using namespace inim;
using namespace fixtures;

namespace {

// A random EIA (zero outside the EIs) and its per-ray drive values.
std::pair<Image, std::vector<float>> randomEia(const EiLayout& L, unsigned seed) {
  Image eia(L.eiaW, L.eiaH, {"R", "G", "B"});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < L.eiaH; ++y)
    for (int x = 0; x < L.eiaW; ++x)
      if (addressAtEiaPixel(L, {x, y}))
        for (int c = 0; c < 3; ++c) eia.at(x, y, c) = u(rng);
  return {eia, driveFromEia(L, eia)};
}

int32_t i32At(const unsigned char* b, size_t off) {
  return int32_t(uint32_t(b[off]) | uint32_t(b[off + 1]) << 8 | uint32_t(b[off + 2]) << 16 | uint32_t(b[off + 3]) << 24);
}
float f32At(const unsigned char* b, size_t off) {
  int32_t i = i32At(b, off);
  float f;
  std::memcpy(&f, &i, 4);
  return f;
}

}  // namespace

TEST(Sdf, HeaderIsExactly208BytesInTheDocumentedLayout) {
  SdfHeader h;
  h.numRays = 18646875;
  h.setDescription("inim test");
  h.sourceFlux = 2.0f;
  h.raySetFlux = 3.0f;
  auto b = encodeSdfHeader(h);
  static_assert(std::tuple_size_v<decltype(b)> == 208);
  EXPECT_EQ(i32At(b.data(), 0), 1010);
  EXPECT_EQ(b[0], 0xF2);  // little-endian 1010
  EXPECT_EQ(b[1], 0x03);
  EXPECT_EQ(uint32_t(i32At(b.data(), 4)), 18646875u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data() + 8)), "inim test");
  EXPECT_EQ(f32At(b.data(), 108), 2.0f);  // source flux
  EXPECT_EQ(f32At(b.data(), 112), 3.0f);  // ray-set flux
  EXPECT_EQ(f32At(b.data(), 116), 0.0f);  // wavelength
  EXPECT_EQ(i32At(b.data(), 136), 4);     // dimension units: mm
  EXPECT_EQ(i32At(b.data(), 192), 2);     // ray format: spectral
  EXPECT_EQ(i32At(b.data(), 196), 0);     // flux type: watts
  EXPECT_EQ(i32At(b.data(), 200), 0);
  EXPECT_EQ(i32At(b.data(), 204), 0);
  SdfHeader back = decodeSdfHeader(b.data());
  EXPECT_EQ(back.numRays, h.numRays);
  EXPECT_EQ(back.descriptionText(), "inim test");
  EXPECT_EQ(std::memcmp(&back, &h, sizeof h), 0);
  // A long description is cut to 99 characters and stays NUL-terminated.
  h.setDescription(std::string(150, 'x'));
  EXPECT_EQ(h.descriptionText().size(), 99u);
}

TEST(Triads, WavelengthChoices) {
  Display d = loadDisplay(defaultDisplayPath());
  TriadWavelengths p = triadWavelengths(d.panel);
  EXPECT_EQ(p.nm, (std::array<double, 3>{625.0, 530.0, 460.0}));
  EXPECT_EQ(triadWavelengths(d.panel, "paper").nm, (std::array<double, 3>{656.0, 566.0, 471.0}));
  EXPECT_EQ(triadWavelengths(d.panel, "zemax-sequential").nm, (std::array<double, 3>{620.0, 525.0, 460.0}));
  expectInputError([&] { triadWavelengths(d.panel, "rgb"); });
}

// Triad wavelengths from a setting's text: a named choice, or three wavelengths in nm that EIA
// formation can tell apart; errors name the setting.
TEST(Triads, WavelengthsFromText) {
  Display d = loadDisplay(defaultDisplayPath());
  EXPECT_EQ(parseTriadWavelengths(d.panel, "paper").nm, paperTriadWavelengths().nm);
  TriadWavelengths w = parseTriadWavelengths(d.panel, "656, 566.25 ,471");
  EXPECT_EQ(w.nm, (std::array<double, 3>{656.0, 566.25, 471.0}));
  EXPECT_EQ(w.source, "given (656/566.2/471 nm)");  // written into SDF descriptions
  for (const char* bad : {"rgb", "656,656.5,471", "656,566", "656,566,471,", "656,566,471,500", "656,x,471",
                          "350,566,471", "656,566,900"})
    EXPECT_EQ(expectInputError([&] { (void)parseTriadWavelengths(d.panel, bad); }).key(), "triad_wavelengths") << bad;
  EXPECT_EQ(expectInputError([&] { (void)parseTriadWavelengths(d.panel, "1,2,3", "run.json: triads"); }).key(),
            "run.json: triads");
}

TEST(Triads, SdfFileSizeAndRoundTrip) {
  EiLayout L = computeLayout(paperDisplay({.cols = 5, .rows = 3, .gapMm = 3.3}));
  RaySet rays = generatePinholeRays(L);
  auto [eia, drive] = randomEia(L, 7);
  TriadWavelengths w = paperTriadWavelengths();
  std::string path = scratchPath("small.sdf");
  TriadOptions opt;
  opt.description = "round trip";
  uint64_t n = writeTriadSdf(path, rays, drive, w, opt);
  const size_t N = rays.size();
  EXPECT_EQ(n, 3 * N);
  EXPECT_EQ(fs::file_size(path), 208u + 32u * 3u * N);
  SdfHeader h;
  std::vector<SdfRay> back = readSdf(path, &h);
  EXPECT_EQ(h.numRays, 3 * N);
  EXPECT_EQ(h.descriptionText(), "round trip");
  EXPECT_EQ(h.rayFormat, 2);
  std::vector<SdfRay> mem = expandTriads(rays, drive, w);
  ASSERT_EQ(back.size(), mem.size());
  EXPECT_EQ(std::memcmp(back.data(), mem.data(), mem.size() * sizeof(SdfRay)), 0);
  // The paper's convention: R, G, B of each display ray, origin at the pinhole, direction
  // negated (pointing back at the panel), wavelength in um, flux = drive value.
  for (size_t i = 0; i < N; i += 11)
    for (int c = 0; c < 3; ++c) {
      const SdfRay& t = back[3 * i + size_t(c)];
      EXPECT_EQ(t.x, rays.ox[i]);
      EXPECT_EQ(t.l, -rays.dx[i]);
      EXPECT_EQ(t.n, -rays.dz[i]);
      EXPECT_EQ(t.flux, drive[3 * i + size_t(c)]);
      EXPECT_FLOAT_EQ(t.wavelengthUm, float(w.nm[size_t(c)] / 1000.0));
    }
  // Skipping black triads shrinks the file and keeps the rest.
  std::vector<float> sparse(drive.size(), 0.0f);
  sparse[4] = 0.5f;
  TriadOptions skip;
  skip.skipZeroFlux = true;
  skip.raySetFluxIsSum = true;
  EXPECT_EQ(writeTriadSdf(path, rays, sparse, w, skip), 1u);
  EXPECT_EQ(fs::file_size(path), 208u + 32u);
  EXPECT_EQ(readSdf(path, &h)[0].flux, 0.5f);
  EXPECT_EQ(h.raySetFlux, 0.5f);
}

TEST(Triads, BadSdfFilesAreInputErrors) {
  EiLayout L = computeLayout(paperDisplay({.cols = 2, .rows = 2, .eiPx = 5, .gapMm = 3.3}));
  RaySet rays = generatePinholeRays(L);
  std::vector<float> drive(rays.size() * 3, 0.25f);
  std::string good = scratchPath("good.sdf");
  writeTriadSdf(good, rays, drive, paperTriadWavelengths());
  std::string bytes = readBytes(good);

  std::string badId = scratchPath("bad_id.sdf");
  std::string b = bytes;
  b[0] = char(0xF3);  // 1011
  std::ofstream(badId, std::ios::binary) << b;
  InputError e = expectInputError([&] { SdfReader r(badId); });
  EXPECT_EQ(e.file(), badId);
  EXPECT_EQ(e.key(), "identifier");

  std::string trunc = scratchPath("truncated.sdf");
  std::ofstream(trunc, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  InputError t = expectInputError([&] { readSdf(trunc); });
  EXPECT_EQ(t.file(), trunc);
  EXPECT_NE(t.expected().find("208 + 32"), std::string::npos);

  std::string fmt = scratchPath("flux_only.sdf");
  b = bytes;
  b[192] = 0;
  std::ofstream(fmt, std::ios::binary) << b;
  EXPECT_EQ(expectInputError([&] { readSdf(fmt); }).key(), "ray format");

  std::string tiny = scratchPath("tiny.sdf");
  std::ofstream(tiny, std::ios::binary) << bytes.substr(0, 100);
  EXPECT_EQ(expectInputError([&] { readSdf(tiny); }).file(), tiny);
  expectInputError([&] { readSdf(scratchPath("missing.sdf")); });
}

// Triads traced straight back to the panel plane rebuild the EIA they were made from.
TEST(Triads, EiaFormationEqualsDirectAssignment) {
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn, EiLayoutKind::LensGrid}) {
    EiLayout L =
        computeLayout(paperDisplay({.cols = 11, .rows = 6, .layout = kind, .gapMm = 3.3, .viewingDistanceMm = 300.0}));
    RaySet rays = generatePinholeRays(L);
    auto [eia, drive] = randomEia(L, 11);
    TriadWavelengths w = triadWavelengths(loadDisplay(defaultDisplayPath()).panel);
    EiaFormation f = formEia(L, expandTriads(rays, drive, w), w);
    EXPECT_EQ(f.binned, 3 * rays.size());
    EXPECT_EQ(f.missed, 0u);
    EXPECT_EQ(f.unknownWavelength, 0u);
    ASSERT_EQ(f.eia.data.size(), eia.data.size());
    float worst = 0.0f;
    for (size_t i = 0; i < eia.data.size(); ++i) worst = std::max(worst, std::abs(f.eia.data[i] - eia.data[i]));
    EXPECT_LE(worst, 1e-6f) << layoutName(kind);
  }
  // Wrong wavelengths are counted, not binned.
  EiLayout L = computeLayout(paperDisplay({.cols = 2, .rows = 2, .eiPx = 5, .gapMm = 3.3}));
  RaySet rays = generatePinholeRays(L);
  std::vector<float> drive(rays.size() * 3, 1.0f);
  EiaFormation f = formEia(L, expandTriads(rays, drive, paperTriadWavelengths()),
                           triadWavelengths(loadDisplay(defaultDisplayPath()).panel));
  EXPECT_EQ(f.binned, 0u);
  EXPECT_EQ(f.unknownWavelength, 3 * rays.size());
}

// The whole prototype: 6,215,625 display rays -> 18,646,875 triads = 596.7 MB, streamed in
// chunks; EIA formation from the file reproduces the EIA. Prints the times.
TEST(Triads, FullDisplaySdfStreamsAndFormsTheEia) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  RaySet rays = generatePinholeRays(L);
  auto [eia, drive] = randomEia(L, 5);
  TriadWavelengths w = triadWavelengths(d.panel, "paper");
  std::string path = scratchPath("full.sdf");
  auto t0 = std::chrono::steady_clock::now();
  uint64_t n = writeTriadSdf(path, rays, drive, w);
  double writeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(n, 18646875u);
  EXPECT_EQ(fs::file_size(path), 208u + 32u * 18646875u);
  auto t1 = std::chrono::steady_clock::now();
  EiaFormation f = formEiaFromSdf(L, path, w);
  double formMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::cout << "[ timing ] SDF write " << n << " triads (" << fs::file_size(path) / 1e6 << " MB) in " << writeMs
            << " ms; EIA formation from the file in " << formMs << " ms\n";
  fs::remove(path);
  EXPECT_EQ(f.binned, n);
  float worst = 0.0f;
  for (size_t i = 0; i < eia.data.size(); ++i) worst = std::max(worst, std::abs(f.eia.data[i] - eia.data[i]));
  EXPECT_LE(worst, 1e-6f);
}

// Found by the sdf fuzz target: a refused header left its file open, so after ~1,000 bad files
// every read failed with "cannot open it". Each of 2,000 bad files must be refused for itself.
TEST(Sdf, ARefusedHeaderClosesItsFile) {
  const std::string bad = fixtures::scratchFile("bad-header.sdf", std::string(300, '\x07'));
  rlimit saved{};
  getrlimit(RLIMIT_NOFILE, &saved);
  rlimit low = saved;
  low.rlim_cur = std::min<rlim_t>(saved.rlim_cur, 256);  // a leak shows within 2,000 reads
  setrlimit(RLIMIT_NOFILE, &low);
  for (int i = 0; i < 2000; ++i) {
    const InputError e = fixtures::expectInputError([&] { (void)readSdf(bad); });
    if (e.key() != "identifier") {
      ADD_FAILURE() << "read " << i << ": " << e.what();
      break;
    }
  }
  setrlimit(RLIMIT_NOFILE, &saved);
}
