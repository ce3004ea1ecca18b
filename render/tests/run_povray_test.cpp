#include "render/run_povray.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "test_util.h"

namespace {

std::string chunk(const std::string& type, const std::string& data) {
  std::string c;
  const auto n = static_cast<std::uint32_t>(data.size());
  for (int shift = 24; shift >= 0; shift -= 8) c += static_cast<char>((n >> shift) & 0xff);
  return c + type + data + "CRC!";  // the CRC is carried, not checked
}

std::string ihdr(int w, int h) {
  std::string d;
  for (int v : {w, h})
    for (int shift = 24; shift >= 0; shift -= 8) d += static_cast<char>((v >> shift) & 0xff);
  return d + std::string("\x08\x02\x00\x00\x00", 5);
}

const std::string kSignature("\x89PNG\r\n\x1a\n", 8);

TEST(StripPngMetadata, DropsTimeAndTextKeepsPixels) {
  const std::string png = kSignature + chunk("IHDR", ihdr(160, 120)) + chunk("gAMA", "abcd") +
                          chunk("tIME", "1234567") + chunk("tEXt", "Comment\0date") +
                          chunk("IDAT", "pixels") + chunk("IEND", "");
  int w = 0, h = 0;
  const std::string clean = mg::render::strip_png_metadata(png, w, h);
  EXPECT_EQ(w, 160);
  EXPECT_EQ(h, 120);
  EXPECT_EQ(clean, kSignature + chunk("IHDR", ihdr(160, 120)) + chunk("gAMA", "abcd") +
                       chunk("IDAT", "pixels") + chunk("IEND", ""));
}

TEST(StripPngMetadata, RefusesNonPng) {
  int w = 0, h = 0;
  EXPECT_THROW(mg::render::strip_png_metadata("GIF89a", w, h), mg::InvalidInput);
  const std::string truncated = kSignature + chunk("IHDR", ihdr(4, 4)) + chunk("IDAT", "pixels");
  EXPECT_THROW(mg::render::strip_png_metadata(truncated.substr(0, truncated.size() - 3), w, h),
               mg::InvalidInput);
  EXPECT_THROW(mg::render::strip_png_metadata(truncated, w, h), mg::InvalidInput);  // no IEND
}

TEST(PovrayArguments, HeadlessPngWithoutJitter) {
  const std::string a = mg::render::povray_arguments("s.pov", "i.png", 160, 120);
  for (const char* flag : {"-D", "+FN8", "+W160", "+H120", "+AM2", "-J", "+Is.pov", "+Oi.png"})
    EXPECT_NE((" " + a + " ").find(std::string(" ") + flag + " "), std::string::npos) << flag;
  mg::render::PovrayOptions opt;
  opt.antialias_threshold = 0;
  opt.threads = 2;
  const std::string b = mg::render::povray_arguments("s.pov", "i.png", 8, 8, opt);
  EXPECT_NE(b.find(" -A "), std::string::npos);
  EXPECT_NE(b.find("+WT2"), std::string::npos);
}

TEST(RenderPng, MissingExecutableIsAnIoErrorAndWritesNothing) {
  mg_test::TempDir dir("render_png");
  mg::render::PovrayOptions opt;
  opt.executable = "mg-no-such-povray";
  try {
    mg::render::render_png("#version 3.7;", dir.file("out.png"), 16, 16, opt);
    ADD_FAILURE() << "no error";
  } catch (const mg::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("'mg-no-such-povray' not found on PATH"),
              std::string::npos)
        << e.what();
  }
  opt.executable = dir.file("nothing-here");
  EXPECT_THROW(mg::render::render_png("", dir.file("out.png"), 16, 16, opt), mg::IoError);
  EXPECT_THROW(mg::render::render_png("", dir.file("out.png"), 0, 16), mg::InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}

}  // namespace
