// PNG files: bit-exact round trips, conversions of other PNG layouts, clear errors
#include "output/png.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// a fresh scratch folder per test program run
fs::path scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("gs_png_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// an image of random bytes (alpha random too when `opaque` is false)
Image noise(int w, int h, bool opaque, std::uint64_t seed) {
  Image img(w, h);
  RngStream rng(seed, 1);
  for (std::size_t k = 0; k < img.rgba.size(); ++k)
    img.rgba[k] = (opaque && k % 4 == 3) ? 255 : static_cast<std::uint8_t>(rng.next_u64() >> 56);
  return img;
}

TEST(Png, RoundTripIsBitExactForOpaqueAndTranslucentImages) {
  // random pixels defeat any "almost equal" shortcut: every byte must come back
  for (bool opaque : {true, false})
    for (auto [w, h] : {std::pair{1, 1}, std::pair{33, 17}, std::pair{320, 240}}) {
      const Image img = noise(w, h, opaque, 7 + w);
      const std::string path =
          (scratch() / ("rt_" + std::to_string(w) + "_" + std::to_string(opaque) + ".png"))
              .string();
      write_png(path, img);
      const Image back = read_png(path);
      ASSERT_EQ(back.width, w);
      ASSERT_EQ(back.height, h);
      EXPECT_TRUE(back.rgba == img.rgba) << w << "x" << h << " opaque " << opaque;
    }
}

TEST(Png, OpaqueImagesAreStoredWithoutAlpha) {
  // colour type byte 25 of the IHDR chunk: 2 = RGB, 6 = RGBA (PNG specification, 11.2.2)
  const std::string a = (scratch() / "opaque.png").string(), b = (scratch() / "alpha.png").string();
  write_png(a, noise(8, 8, true, 1));
  write_png(b, noise(8, 8, false, 1));
  auto colour_type = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    char head[26];
    in.read(head, 26);
    return static_cast<int>(head[25]);
  };
  EXPECT_EQ(colour_type(a), 2);
  EXPECT_EQ(colour_type(b), 6);
}

TEST(Png, MissingUnwritableAndCorruptFilesNameThePath) {
  const std::string missing = (scratch() / "no_such.png").string();
  try {
    read_png(missing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), missing);
  }
  const std::string bad_dir = (scratch() / "no_dir" / "x.png").string();
  try {
    write_png(bad_dir, noise(2, 2, true, 3));
    FAIL();
  } catch (const OutputError& e) {
    // an unwritable output is an output failure (exit 5), naming the path
    EXPECT_EQ(std::string(e.what()).rfind(bad_dir, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos);
  }
  const std::string text = (scratch() / "text.png").string();
  std::ofstream(text) << "this is not a PNG file";
  EXPECT_THROW(read_png(text), InputError);
  EXPECT_THROW(write_png(text, Image()), InputError);
}

}  // namespace
}  // namespace gs
