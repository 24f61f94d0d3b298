// A minimal PNG reader for tests (8-bit RGB or RGBA, not interlaced: what
// Chromium's screenshots are), written from the PNG specification: chunks,
// zlib-compressed IDAT, per-row filters None/Sub/Up/Average/Paeth.
#pragma once

#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamid::testing {

struct PngImage {
  int width = 0;
  int height = 0;
  std::vector<std::array<std::uint8_t, 3>> rgb;  // row-major

  const std::array<std::uint8_t, 3>& At(int x, int y) const { return rgb[static_cast<std::size_t>(y) * width + x]; }
};

inline std::uint32_t BigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

inline PngImage ReadPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  static const std::uint8_t kSignature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
    throw std::runtime_error(path + ": not a PNG file");
  PngImage image;
  int color_type = 0, depth = 0;
  std::vector<std::uint8_t> compressed;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = BigEndian32(&bytes[at]);
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    const std::uint8_t* data = &bytes[at + 8];
    if (type == "IHDR") {
      image.width = static_cast<int>(BigEndian32(data));
      image.height = static_cast<int>(BigEndian32(data + 4));
      depth = data[8];
      color_type = data[9];
      if (data[12] != 0) throw std::runtime_error(path + ": interlaced PNG not supported");
    } else if (type == "IDAT") {
      compressed.insert(compressed.end(), data, data + length);
    } else if (type == "IEND") {
      break;
    }
    at += 12 + length;
  }
  if (depth != 8 || (color_type != 2 && color_type != 6))
    throw std::runtime_error(path + ": only 8-bit RGB/RGBA PNG supported");
  const std::size_t channels = color_type == 6 ? 4 : 3;
  const std::size_t stride = channels * static_cast<std::size_t>(image.width);
  std::vector<std::uint8_t> raw((stride + 1) * static_cast<std::size_t>(image.height));
  uLongf raw_size = raw.size();
  if (uncompress(raw.data(), &raw_size, compressed.data(), compressed.size()) != Z_OK || raw_size != raw.size())
    throw std::runtime_error(path + ": cannot inflate the image data");
  std::vector<std::uint8_t> previous(stride, 0), row(stride);
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height);
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* line = &raw[static_cast<std::size_t>(y) * (stride + 1)];
    const int filter = line[0];
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= channels ? row[i - channels] : 0;
      const int b = previous[i];
      const int c = i >= channels ? previous[i - channels] : 0;
      int predictor = 0;
      switch (filter) {
        case 1: predictor = a; break;
        case 2: predictor = b; break;
        case 3: predictor = (a + b) / 2; break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default: break;
      }
      row[i] = static_cast<std::uint8_t>(line[1 + i] + predictor);
    }
    for (int x = 0; x < image.width; ++x)
      image.rgb[static_cast<std::size_t>(y) * image.width + x] = {row[x * channels], row[x * channels + 1],
                                                                  row[x * channels + 2]};
    previous = row;
  }
  return image;
}

}  // namespace beamid::testing
