#include "dataset/dataset_image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "core/input_file.h"
#include "core/error.h"
#include "core/quiet_stderr.h"
#include "core/size_budget.h"

namespace inim {

namespace {

// Open with straight (unassociated) alpha left as stored: OIIO would otherwise premultiply
// PNG colour itself, and do it in linear light, which is not what NeRF training does.
std::unique_ptr<OIIO::ImageInput> openImage(const std::string& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  checkInputFile(path);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw InputError(path, "", "", "a readable image (" + OIIO::geterror() + ")");
  return in;
}

int alphaChannel(const OIIO::ImageSpec& spec) {
  if (spec.alpha_channel >= 0) return spec.alpha_channel;
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[c] == "A" || spec.channelnames[c] == "a") return c;
  return -1;
}

}  // namespace

ImageHeader readImageHeader(const std::string& path) {
  LibraryStderrSilenced quiet(path);
  auto in = openImage(path);
  const OIIO::ImageSpec& spec = in->spec();
  ImageHeader h{spec.width, spec.height, spec.nchannels, alphaChannel(spec) >= 0};
  in->close();
  return h;
}

Image downscaleImage(const Image& img, int f) {
  if (f <= 1) return img;
  const int C = img.numChannels();
  const int W = downscaledSize(img.width, f), H = downscaledSize(img.height, f);
  if (img.width % f == 0 && img.height % f == 0) {
    Image out(W, H, img.channels);
    const float inv = 1.0f / float(f * f);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        for (int c = 0; c < C; ++c) {
          float s = 0.0f;
          for (int j = 0; j < f; ++j)
            for (int i = 0; i < f; ++i) s += img.at(x * f + i, y * f + j, c);
          out.at(x, y, c) = s * inv;
        }
    return out;
  }
  // Not a multiple: a filtered resize through OIIO.
  OIIO::ImageSpec srcSpec(img.width, img.height, C, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf src(srcSpec, const_cast<float*>(img.data.data()));
  OIIO::ImageSpec dstSpec(W, H, C, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf dst(dstSpec);
  if (!OIIO::ImageBufAlgo::resize(dst, src, "box", float(f)))
    throw std::runtime_error("image resize failed: " + dst.geterror());
  Image out(W, H, img.channels);
  dst.get_pixels(OIIO::ROI(0, W, 0, H, 0, 1, 0, C), OIIO::TypeDesc::FLOAT, out.data.data());
  return out;
}

Image readDatasetImage(const std::string& path, const glm::vec3& bg, int downscale, bool* hadAlpha) {
  LibraryStderrSilenced quiet(path);
  auto in = openImage(path);
  const OIIO::ImageSpec& spec = in->spec();
  const int W = spec.width, H = spec.height, N = spec.nchannels;
  checkAllocation(path, "size",
                  std::to_string(W) + " x " + std::to_string(H) + " px x " + std::to_string(N) + " channels",
                  {{double(W) * H * N, 2 * sizeof(float)}}, "the image and its copy");
  std::vector<float> px(size_t(W) * H * N);
  if (!in->read_image(0, 0, 0, N, OIIO::TypeDesc::FLOAT, px.data()))
    throw InputError(path, "", "", "a readable image (" + in->geterror() + ")");
  const int a = alphaChannel(spec);
  // With the hint above, formats that store straight alpha (PNG, TIFF...) say so here;
  // EXR (premultiplied by definition) does not.
  const bool straight = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  in->close();
  if (hadAlpha) *hadAlpha = a >= 0;

  int colour[3];
  {
    std::vector<int> cs;
    for (int c = 0; c < N && cs.size() < 3; ++c)
      if (c != a) cs.push_back(c);
    if (cs.empty()) throw InputError(path, "channels", std::to_string(N), "an image with colour channels");
    for (int i = 0; i < 3; ++i) colour[i] = cs[std::min<size_t>(i, cs.size() == 3 ? i : 0)];
  }

  Image rgb(W, H, {"R", "G", "B"});
  for (size_t p = 0; p < size_t(W) * H; ++p) {
    const float* s = &px[p * N];
    float alpha = a >= 0 ? std::clamp(s[a], 0.0f, 1.0f) : 1.0f;
    for (int c = 0; c < 3; ++c) {
      float v = s[colour[c]];
      if (!std::isfinite(v) || (a >= 0 && !std::isfinite(s[a])))
        throw InputError(path, "pixel (" + std::to_string(p % W) + ", " + std::to_string(p / W) + ")",
                         "non-finite", "finite values");
      float premult = (a < 0) ? v : (straight ? v * alpha : v);
      rgb.data[p * 3 + c] = premult + bg[c] * (1.0f - alpha);
    }
  }
  return downscaleImage(rgb, downscale);
}

}  // namespace inim
