#include <unexmin/sim/texture_image.h>

#include <unexmin/core/error.h>

#include <jpeglib.h>
#include <png.h>

#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <memory>

namespace unexmin {
namespace sim {
namespace {

TextureImage readPng(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw ConfigError(path + ": damaged PNG image: " + image.message);
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr)) {
    const std::string why = image.message;
    png_image_free(&image);
    throw ConfigError(path + ": damaged PNG image: " + why);
  }
  return TextureImage(static_cast<int>(image.width), static_cast<int>(image.height), std::move(rgb));
}

struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void jpegFail(j_common_ptr info) {
  auto* e = reinterpret_cast<JpegError*>(info->err);
  e->manager.format_message(info, e->message);
  std::longjmp(e->jump, 1);
}

TextureImage readJpeg(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file)
    throw ConfigError(path + ": cannot open the image");
  jpeg_decompress_struct info{};
  JpegError error;
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = jpegFail;
  std::vector<std::uint8_t> rgb;  // before setjmp: nothing with a destructor is created between it and longjmp
  int width = 0, height = 0;
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&info);
    throw ConfigError(path + ": damaged JPEG image: " + error.message);
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file.get());
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  width = static_cast<int>(info.output_width);
  height = static_cast<int>(info.output_height);
  rgb.resize(static_cast<std::size_t>(width) * height * 3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = rgb.data() + static_cast<std::size_t>(info.output_scanline) * width * 3;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return TextureImage(width, height, std::move(rgb));
}

const std::array<float, 256>& linearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

}  // namespace

TextureImage TextureImage::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ConfigError(path + ": cannot open the image");
  unsigned char magic[4] = {};
  in.read(reinterpret_cast<char*>(magic), sizeof(magic));
  if (in.gcount() == 4 && magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G')
    return readPng(path);
  if (in.gcount() >= 2 && magic[0] == 0xFF && magic[1] == 0xD8)
    return readJpeg(path);
  throw ConfigError(path + ": neither a PNG nor a JPEG image");
}

TextureImage::TextureImage(int width, int height, std::vector<std::uint8_t> rgb)
    : width_(width), height_(height), rgb_(std::move(rgb)) {
  if (width < 1 || height < 1 || rgb_.size() != static_cast<std::size_t>(width) * height * 3)
    throw ConfigError("texture image: " + formatNumber(width) + " x " + formatNumber(height) + " texels need " +
                      formatNumber(3.0 * width * height) + " bytes, got " + formatNumber(rgb_.size()));
}

float TextureImage::linear(std::uint8_t code) {
  return linearTable()[code];
}

Eigen::Array3f TextureImage::sample(float u, float v) const {
  // Texel coordinates with the texel centres at integers, rows counted from the top.
  const float s = (u - std::floor(u)) * width_ - 0.5f;
  const float t = (1.0f - (v - std::floor(v))) * height_ - 0.5f;
  const float s0 = std::floor(s), t0 = std::floor(t);
  const float fs = s - s0, ft = t - t0;
  const auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  const int i0 = wrap(static_cast<int>(s0), width_), i1 = wrap(i0 + 1, width_);
  const int j0 = wrap(static_cast<int>(t0), height_), j1 = wrap(j0 + 1, height_);
  const auto& lin = linearTable();
  const auto texel = [&](int i, int j) {
    const std::uint8_t* p = &rgb_[3 * (static_cast<std::size_t>(j) * width_ + i)];
    return Eigen::Array3f(lin[p[0]], lin[p[1]], lin[p[2]]);
  };
  return (1 - ft) * ((1 - fs) * texel(i0, j0) + fs * texel(i1, j0)) +
         ft * ((1 - fs) * texel(i0, j1) + fs * texel(i1, j1));
}

}  // namespace sim
}  // namespace unexmin
