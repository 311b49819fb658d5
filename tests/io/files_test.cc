// io/files.h: what the all-or-nothing writers leave behind when they succeed and when they do not.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

// What another program (gnuplot) does with the temporary path it is given.
void write_by_name(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::trunc) << text; }

TEST(PendingFile, BecomesTheDestinationOnlyOnCommit) {
  const test::TempDir dir;
  const std::string destination = (dir / "plot.svg").string();
  io::write_file_atomically(destination, "old");
  {
    io::PendingFile abandoned(destination);
    write_by_name(abandoned.path(), "half");
  }
  EXPECT_EQ(test::read_text(destination), "old");
  {
    io::PendingFile file(destination);
    write_by_name(file.path(), "new");
    file.commit();
  }
  EXPECT_EQ(test::read_text(destination), "new");
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << "left behind: " << entry.path();
  }
  EXPECT_EQ(entries, 1);
}

TEST(PendingFile, TwoWritersOfOneDestinationNeverShareATemporary) {
  const test::TempDir dir;
  const std::string destination = (dir / "plot.svg").string();
  io::PendingFile first(destination), second(destination);
  EXPECT_NE(first.path(), second.path());
  write_by_name(first.path(), "first");
  write_by_name(second.path(), "second");
  first.commit();
  second.commit();
  EXPECT_EQ(test::read_text(destination), "second");
}

TEST(PendingFile, MissingDirectoryIsAnOutputErrorNamingTheDestination) {
  const test::TempDir dir;
  const std::string destination = dir.string() + "/no/such/dir/plot.svg";
  try {
    io::PendingFile file(destination);
    FAIL() << "no error for " << destination;
  } catch (const io::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(destination), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace zhf
