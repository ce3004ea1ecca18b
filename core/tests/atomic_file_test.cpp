#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>

#include "test_util.h"

namespace {

std::set<std::string> entries(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(folder))
    names.insert(e.path().filename().string());
  return names;
}

TEST(AtomicFile, UncommittedLeavesNothing) {
  mg_test::TempDir dir("atomic");
  {
    mg::AtomicFile file(dir.file("a.off"));
    std::ofstream(file.temp_path()) << "partial\n";
  }
  EXPECT_TRUE(entries(dir.file("")).empty());
}

TEST(AtomicFile, FilesWrittenTogetherAppearTogetherOrNotAtAll) {
  mg_test::TempDir dir("atomic");
  const std::string a = dir.file("a.txt"), b = dir.file("b.txt");
  auto text = [](std::ostream& out) { out << "x\n"; };
  // A writer throwing: neither file, no temporary file.
  EXPECT_THROW(mg::write_files_together(
                   {{a, text}, {b, [](std::ostream&) { throw std::runtime_error("no"); }}}),
               std::runtime_error);
  EXPECT_TRUE(entries(dir.file("")).empty());
  // The second rename failing (its target a folder): the first, already renamed, is removed.
  std::filesystem::create_directory(b);
  EXPECT_THROW(mg::write_files_together({{a, text}, {b, text}}), mg::IoError);
  EXPECT_EQ(entries(dir.file("")), std::set<std::string>{"b.txt"});
  std::filesystem::remove(b);
  mg::write_files_together({{a, text}, {"", text}, {b, text}});
  EXPECT_EQ(entries(dir.file("")), (std::set<std::string>{"a.txt", "b.txt"}));
}

TEST(AtomicFile, OutputPathsAreChecked) {
  mg_test::TempDir dir("atomic");
  const std::string in = dir.write("in.ma", "0 0 0 1\n");
  EXPECT_NO_THROW(mg::check_output_path(dir.file("out.off"), {in}));
  EXPECT_THROW(mg::check_output_path(in, {in}), mg::InvalidInput);
  EXPECT_THROW(mg::check_output_path(dir.file("none/out.off"), {in}), mg::InvalidInput);
  std::filesystem::create_directory(dir.file("d.off"));
  try {
    mg::check_output_path(dir.file("d.off"), {in});
    ADD_FAILURE() << "a folder accepted as output";
  } catch (const mg::InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), dir.file("d.off") + ": output path is a folder");
  }
}

}  // namespace
