// Pinhole display rays, the ray-index mapping, and the Zemax text / inim binary ray files.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "display/display.h"
#include "fixtures.h"
#include "rays/pinhole_rays.h"
#include "rays/ray_binary.h"
#include "rays/zemax_ray_text.h"

namespace fs = std::filesystem;
using namespace inim;
using namespace fixtures;

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> r;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) r.push_back(l);
  return r;
}

}  // namespace

// The paper's macro: a 25 x 25 EI of 0.0395 mm pixels at a 3 mm gap wrote the corner ray
// direction (0.15419750, 0.15419750, 0.97593353). It is the first line of the file: the
// bottom-left pixel (x = y = -12 px = -0.474 mm), whose chief ray through the pinhole leans
// up and right. Ray order: x outer, y inner, both increasing.
TEST(PinholeRays, CornerDirectionMatchesThePaperMacro) {
  EiLayout L = computeLayout(paperDisplay({.cols = 1, .rows = 1, .gapMm = 3.0}));
  std::string path = scratchPath("one_ei.txt");
  writeZemaxEiRayText(path, L, 0, 0);
  auto ls = lines(readBytes(path));
  ASSERT_EQ(ls.size(), 625u);
  EXPECT_EQ(ls[0], "0.00000000, 0.00000000, 0.00000000, 0.15419750, 0.15419750, 0.97593353");
  EXPECT_EQ(ls[24], "0.00000000, 0.00000000, 0.00000000, 0.15419750, -0.15419750, 0.97593353");
  EXPECT_EQ(ls[600], "0.00000000, 0.00000000, 0.00000000, -0.15419750, 0.15419750, 0.97593353");
  EXPECT_EQ(ls[624], "0.00000000, 0.00000000, 0.00000000, -0.15419750, -0.15419750, 0.97593353");
  EXPECT_EQ(ls[312], "0.00000000, 0.00000000, 0.00000000, 0.00000000, 0.00000000, 1.00000000");
  // Ray 0 is the bottom-left pixel of the EI: image row 24, column 0.
  EXPECT_EQ(rayAddress(L, 0), (RayAddress{0, 0, 0, 24}));

  // Same ray in the full prototype at g = 3 mm: the centre EI (76, 32) sits on the axis.
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout F = computeLayout(d).withGap(3.0);
  RayD r = pinholeRay(F, RayAddress{76, 32, 0, 24});
  EXPECT_NEAR(r.d.x, 0.15419750, 5e-9);
  EXPECT_NEAR(r.d.y, 0.15419750, 5e-9);
  EXPECT_NEAR(r.d.z, 0.97593353, 5e-9);
  EXPECT_NEAR(r.o.x, 0.0, 1e-12);
  EXPECT_EQ(formatZemaxRayLine(std::array<double, 6>{0, 0, 0, r.d.x, r.d.y, r.d.z}.data()),
            "0.00000000, 0.00000000, 0.00000000, 0.15419750, 0.15419750, 0.97593353");
}

TEST(PinholeRays, IndexMappingRoundTrips) {
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn}) {
    EiLayout L = computeLayout(paperDisplay({.cols = 7,
                                             .rows = 4,
                                             .eiPx = 5,
                                             .layout = kind,
                                             .gapMm = 3.3,
                                             .lensPitchMm = 0.25,
                                             .viewingDistanceMm = 30.0}));
    int64_t mapped = 0;
    std::vector<int> hits(size_t(L.eiaW) * L.eiaH, 0);
    for (int64_t r = 0; r < L.numRays(); ++r) {
      RayAddress a = rayAddress(L, r);
      ASSERT_EQ(rayIndex(L, a), r);
      PixelCoord p = eiaPixel(L, a);
      ASSERT_TRUE(p.col >= 0 && p.col < L.eiaW && p.row >= 0 && p.row < L.eiaH);
      hits[size_t(p.row) * L.eiaW + p.col]++;
      auto back = addressAtEiaPixel(L, p);
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(*back, a);
      PixelCoord q = panelPixel(L, a);
      EXPECT_EQ(q, (PixelCoord{p.col + L.panelCol0, p.row + L.panelRow0}));
      EXPECT_EQ(*addressAtPanelPixel(L, q), a);
    }
    for (int row = 0; row < L.eiaH; ++row)
      for (int col = 0; col < L.eiaW; ++col) {
        int h = hits[size_t(row) * L.eiaW + col];
        EXPECT_LE(h, 1);
        EXPECT_EQ(h == 1, addressAtEiaPixel(L, {col, row}).has_value());
        mapped += h;
      }
    EXPECT_EQ(mapped, L.numRays());
    if (kind == EiLayoutKind::ToedIn) {
      EXPECT_GT(int64_t(L.eiaW) * L.eiaH, L.numRays());  // gaps
    }
  }
  EiLayout L = computeLayout(paperDisplay({.cols = 3, .rows = 2, .eiPx = 4, .gapMm = 3.0}));
  // EI order: k outer, EI rows from the bottom; pixels: i outer, rows from the bottom.
  EXPECT_EQ(rayAddress(L, 1), (RayAddress{0, 1, 0, 2}));
  EXPECT_EQ(rayAddress(L, 4), (RayAddress{0, 1, 1, 3}));
  EXPECT_EQ(rayAddress(L, 16), (RayAddress{0, 0, 0, 3}));
  EXPECT_EQ(rayAddress(L, 32), (RayAddress{1, 1, 0, 3}));
}

TEST(PinholeRays, RaysRunFromPixelCentresThroughPinholes) {
  for (EiLayoutKind kind : {EiLayoutKind::Parallel, EiLayoutKind::ToedIn, EiLayoutKind::LensGrid}) {
    EiLayout L = computeLayout(paperDisplay({.cols = 9, .rows = 5, .layout = kind, .gapMm = 3.3}));
    RaySet rays = generatePinholeRays(L);
    ASSERT_EQ(int64_t(rays.size()), L.numRays());
    for (int64_t r = 0; r < L.numRays(); r += 7) {
      Ray ray = rays.ray(size_t(r));
      RayAddress a = rayAddress(L, r);
      EXPECT_NEAR(glm::length(ray.d), 1.0f, 1e-6f);
      EXPECT_GT(ray.d.z, 0.0f);
      EXPECT_FLOAT_EQ(ray.o.x, float(L.pinholeX[size_t(a.k)]));
      EXPECT_FLOAT_EQ(ray.o.y, float(L.pinholeY[size_t(a.l)]));
      EXPECT_EQ(ray.o.z, 0.0f);
      // Back to the panel plane: the pixel centre.
      Point3d c = pixelCentre(L, a);
      double t = -L.gapMm / double(ray.d.z);
      EXPECT_NEAR(ray.o.x + t * ray.d.x, c.x, 2e-6);
      EXPECT_NEAR(ray.o.y + t * ray.d.y, c.y, 2e-6);
      RayD rd = pinholeRay(L, a);
      EXPECT_NEAR(rd.d.x, ray.d.x, 1e-7);
      EXPECT_NEAR(rd.d.z, ray.d.z, 1e-7);
    }
    // Parallel: the centre pixel of every EI (odd size) emits along +z.
    if (kind == EiLayoutKind::Parallel) {
      for (int k = 0; k < L.eiCols; ++k) {
        Ray c = rays.ray(size_t(rayIndex(L, {k, 2, 12, 12})));
        EXPECT_EQ(c.d.x, 0.0f);
        EXPECT_EQ(c.d.z, 1.0f);
      }
    }
  }
}

// All 6,215,625 rays of the default display; prints the time. Deterministic across thread counts.
TEST(PinholeRays, FullDisplayIsFastAndDeterministic) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  generatePinholeRays(L);  // warm up (page faults of the first allocation)
  auto t0 = std::chrono::steady_clock::now();
  RaySet rays = generatePinholeRays(L);
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "[ timing ] " << rays.size() << " pinhole rays in " << ms << " ms on " << hardwareThreads()
            << " threads (" << rays.size() * 24 / (1 << 20) << " MiB)\n";
  EXPECT_EQ(rays.size(), 6215625u);
  RaySet one;
  {
    ThreadLimit limit(1);
    one = generatePinholeRays(L);
  }
  EXPECT_EQ(one.dx, rays.dx);
  EXPECT_EQ(one.dy, rays.dy);
  EXPECT_EQ(one.dz, rays.dz);
  EXPECT_EQ(one.ox, rays.ox);
  // The paper's pinhole grid: EI (k, l) at ((k - 76) 0.9875, (32 - l) 0.9875).
  Ray r = rays.ray(size_t(rayIndex(L, {0, 64, 0, 24})));
  EXPECT_NEAR(r.o.x, -75.05f, 1e-5f);
  EXPECT_NEAR(r.o.y, -31.6f, 1e-5f);
}

// A point at depth z: for every EI that sees it, the pixel the pinhole geometry predicts is
// the one whose chief ray passes closest to the point (brute force over the EI's rays).
TEST(PinholeRays, PredictedPixelForAPointMatchesBruteForce) {
  Display d = loadDisplay(defaultDisplayPath());
  for (double gap : {3.3, 4.0}) {
    EiLayout L = computeLayout(d).withGap(gap);
    for (Point3d p : {Point3d(5.3, -2.17, 20.0), Point3d(-31.7, 12.4, -20.0), Point3d(60.1, 25.3, 55.0),
                      Point3d(0.21, 0.13, -12.5), Point3d(-70.0, -30.0, 9.0)}) {
      int seen = 0, agree = 0;
      for (int k = 0; k < L.eiCols; ++k)
        for (int l = 0; l < L.eiRows; ++l) {
          auto pred = predictPixelForPoint(L, k, l, p);
          if (!pred) continue;
          ++seen;
          double best = 1e300;
          RayAddress arg{};
          for (int i = 0; i < L.eiW; ++i)
            for (int j = 0; j < L.eiH; ++j) {
              RayD r = pinholeRay(L, RayAddress{k, l, i, j});
              double dist = glm::length(glm::cross(p - r.o, r.d));
              if (dist < best) best = dist, arg = {k, l, i, j};
            }
          agree += (arg == *pred);
        }
      EXPECT_GE(seen, 4) << "z = " << p.z;
      std::cout << "[ point  ] (" << p.x << ", " << p.y << ", " << p.z << ") g " << gap << ": " << agree << " of "
                << seen << " EIs agree\n";
      EXPECT_GE(agree, 0.95 * seen) << "point " << p.x << ", " << p.y << ", " << p.z << " gap " << gap;
    }
  }
  EiLayout L = computeLayout(d);
  EXPECT_FALSE(predictPixelForPoint(L, 0, 0, Point3d(50.0, 0.0, 10.0)).has_value());  // far outside
  EXPECT_FALSE(predictPixelForPoint(L, 76, 32, Point3d(0.1, 0.1, 0.0)).has_value());  // on the pinhole plane
}

TEST(ZemaxRayText, WriteReadRoundTrip) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  L.eiCols = 20;  // a 20 x 10 EI corner of the prototype: 125,000 rays
  L.eiRows = 10;
  L.eiCol0.resize(20);
  L.pinholeX.resize(20);
  L.eiRow0.resize(10);
  L.pinholeY.resize(10);
  RaySet rays = generatePinholeRays(L);
  std::string a = scratchPath("rays_a.txt"), b = scratchPath("rays_b.txt");
  writeZemaxRayText(a, rays);
  RaySet back = readZemaxRayText(a);
  ASSERT_EQ(back.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    for (auto [u, v] : {std::pair{rays.ox[i], back.ox[i]}, {rays.oy[i], back.oy[i]}, {rays.oz[i], back.oz[i]},
                        {rays.dx[i], back.dx[i]}, {rays.dy[i], back.dy[i]}, {rays.dz[i], back.dz[i]}})
      ASSERT_NEAR(u, v, 5e-9 + 6e-8 * std::abs(u)) << "ray " << i;  // %.8f and float rounding
  }
  // Text is a fixed point: read -> write gives the same bytes.
  writeZemaxRayText(b, back);
  EXPECT_EQ(readBytes(a), readBytes(b));
  // The double-precision export of the layout prints the same lines up to the last digit.
  std::string c = scratchPath("rays_c.txt");
  writeZemaxRayText(c, L);
  RaySet fromDouble = readZemaxRayText(c);
  for (size_t i = 0; i < rays.size(); i += 97) EXPECT_NEAR(fromDouble.dx[i], rays.dx[i], 1e-7);
}

TEST(ZemaxRayText, ReadsUtf16WithBomCrlfAndHeaderLines) {
  EiLayout L = computeLayout(paperDisplay({.cols = 2, .rows = 2, .eiPx = 5, .gapMm = 3.0}));
  RaySet rays = generatePinholeRays(L);
  // As the macro writes: UTF-16LE, BOM, CRLF, two header lines (one with a non-ASCII char).
  std::string text = "Ray data \xB5m: x, y, z, l, m, n\r\nNumber of rays: 100\r\n";
  std::string utf8 = scratchPath("utf8.txt");
  writeZemaxRayText(utf8, rays);
  for (const auto& l : lines(readBytes(utf8))) text += l + "\r\n";
  std::string bytes = "\xFF\xFE";
  for (unsigned char ch : text) bytes += std::string{char(ch), '\0'};  // Latin-1 to UTF-16LE
  std::string path = scratchPath("macro_utf16.txt");
  std::ofstream(path, std::ios::binary) << bytes;
  std::vector<std::string> header;
  RaySet back = readZemaxRayText(path, &header);
  ASSERT_EQ(header.size(), 2u);
  EXPECT_EQ(header[1], "Number of rays: 100");
  ASSERT_EQ(back.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_NEAR(back.dx[i], rays.dx[i], 1e-8);
    EXPECT_NEAR(back.dz[i], rays.dz[i], 1e-8);
    EXPECT_NEAR(back.ox[i], rays.ox[i], 1e-8);
  }
  // The writer's own UTF-16 / CRLF / header mode reads back the same.
  std::string w = scratchPath("written_utf16.txt");
  writeZemaxRayText(w, rays, {true, true, zemaxMacroHeader(int64_t(rays.size()))});
  std::string wb = readBytes(w);
  EXPECT_EQ(wb.substr(0, 2), "\xFF\xFE");
  EXPECT_NE(wb.find(std::string("\r\0\n\0", 4)), std::string::npos);
  header.clear();
  RaySet back2 = readZemaxRayText(w, &header);
  EXPECT_EQ(header.size(), 2u);
  EXPECT_EQ(back2.dx, back.dx);
}

TEST(ZemaxRayText, BadFilesAreInputErrors) {
  std::string p = scratchPath("bad.txt");
  std::ofstream(p) << "header\n0, 0, 0, 0, 0, 1\n0, 0, 0, 0, 0\n";
  InputError e = expectInputError([&] { readZemaxRayText(p); });
  EXPECT_EQ(e.file(), p);
  EXPECT_EQ(e.key(), "line 3");
  std::ofstream(p) << "0, 0, 0, 0, 0.5, 1\n";
  EXPECT_NE(expectInputError([&] { readZemaxRayText(p); }).expected().find("unit"), std::string::npos);
  std::ofstream(p) << "just a header\n";
  expectInputError([&] { readZemaxRayText(p); });
  expectInputError([&] { readZemaxRayText(scratchPath("does_not_exist.txt")); });
}

TEST(RayBinary, RoundTripIsExactAndBadFilesFail) {
  EiLayout L = computeLayout(paperDisplay({.cols = 6, .rows = 3, .layout = EiLayoutKind::ToedIn, .gapMm = 3.3}));
  RaySet rays = generatePinholeRays(L);
  std::string p = scratchPath("rays.irays");
  writeRayBinary(p, rays, RayBinaryInfo::fromLayout(L));
  EXPECT_EQ(fs::file_size(p), 48u + 24u * rays.size());
  RayBinaryInfo info;
  RaySet back = readRayBinary(p, &info);
  EXPECT_EQ(back.ox, rays.ox);
  EXPECT_EQ(back.oy, rays.oy);
  EXPECT_EQ(back.oz, rays.oz);
  EXPECT_EQ(back.dx, rays.dx);
  EXPECT_EQ(back.dy, rays.dy);
  EXPECT_EQ(back.dz, rays.dz);
  EXPECT_EQ(info.eiCols, 6);
  EXPECT_EQ(info.eiH, 25);
  EXPECT_FLOAT_EQ(info.gapMm, 3.3f);

  std::string bytes = readBytes(p);
  std::string t = scratchPath("truncated.irays");
  std::ofstream(t, std::ios::binary) << bytes.substr(0, bytes.size() - 4);
  EXPECT_EQ(expectInputError([&] { readRayBinary(t); }).file(), t);
  std::string m = scratchPath("magic.irays");
  std::ofstream(m, std::ios::binary) << ("X" + bytes.substr(1));
  EXPECT_EQ(expectInputError([&] { readRayBinary(m); }).key(), "magic");
}

TEST(PinholeRays, DriveValuesFromAndToTheEia) {
  EiLayout L = computeLayout(paperDisplay({.cols = 8,
                                           .rows = 5,
                                           .eiPx = 6,
                                           .layout = EiLayoutKind::ToedIn,
                                           .gapMm = 3.3,
                                           .lensPitchMm = 0.25,
                                           .viewingDistanceMm = 40.0}));
  Image eia(L.eiaW, L.eiaH, {"R", "G", "B"});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < L.eiaH; ++y)
    for (int x = 0; x < L.eiaW; ++x)
      for (int c = 0; c < 3; ++c) eia.at(x, y, c) = addressAtEiaPixel(L, {x, y}) ? u(rng) : 0.0f;
  std::vector<float> drive = driveFromEia(L, eia);
  EXPECT_EQ(drive.size(), size_t(L.numRays()) * 3);
  Image back = eiaFromDrive(L, drive);
  EXPECT_EQ(back.data, eia.data);
  Image wrong(L.eiaW + 1, L.eiaH, {"R", "G", "B"});
  expectInputError([&] { driveFromEia(L, wrong); });
}
