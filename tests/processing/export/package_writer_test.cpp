// The streaming package writer: zips read back with libarchive's reader and python's zipfile, text
// deflated and images stored, ZIP64 records python understands, unsafe and duplicate names refused, and an
// unfinished package that leaves no file and the previous package untouched.
#include "processing/export/package_writer.h"

#include <archive.h>
#include <archive_entry.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "model/error.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

fs::path test_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("plenopath_package_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(rng() & 0xFF);
  return s;
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream b;
  b << in.rdbuf();
  return b.str();
}

// Every entry of `zip` as libarchive's reader sees it.
std::map<std::string, std::string> read_with_libarchive(const fs::path& zip) {
  std::map<std::string, std::string> entries;
  struct archive* a = archive_read_new();
  archive_read_support_format_zip(a);
  EXPECT_EQ(archive_read_open_filename(a, zip.c_str(), 1 << 16), ARCHIVE_OK) << archive_error_string(a);
  struct archive_entry* e = nullptr;
  while (archive_read_next_header(a, &e) == ARCHIVE_OK) {
    std::string data;
    char buffer[1 << 14];
    la_ssize_t n;
    while ((n = archive_read_data(a, buffer, sizeof buffer)) > 0)
      data.append(buffer, static_cast<std::size_t>(n));
    EXPECT_EQ(n, 0) << archive_error_string(a);
    entries[archive_entry_pathname(e)] = data;
  }
  archive_read_free(a);
  return entries;
}

// Runs python3 with `script` on `zip`; true when it exits 0.
bool python_accepts(const std::string& script, const fs::path& zip) {
  const fs::path file = zip.string() + ".check.py";
  std::ofstream(file) << script;
  const std::string cmd = "/usr/bin/python3 '" + file.string() + "' '" + zip.string() + "'";
  return std::system(cmd.c_str()) == 0;
}

const std::string kText = [] {
  std::string s;
  for (int i = 0; i < 2000; ++i) s += "{\"frame\": " + std::to_string(i) + ", \"x\": 1.5}\n";
  return s;
}();
const std::string kImage = random_bytes(300000, 7);  // incompressible, as a JPEG

TEST(PackageWriter, ZipReadsBackWithLibarchive) {
  const fs::path dir = test_dir("libarchive");
  const fs::path zip = dir / "tour.zip";
  PackageWriter w(zip.string());
  w.add("tour.json", kText);
  w.add("images/k000000_full.jpg", kImage.data(), kImage.size());
  w.add("empty.txt", "");
  std::ofstream(dir / "clip.mp4", std::ios::binary) << kImage.substr(0, 5000);
  w.add_file("media/clip.mp4", (dir / "clip.mp4").string());
  const std::uintmax_t bytes = w.commit();
  EXPECT_EQ(bytes, fs::file_size(zip));
  const auto entries = read_with_libarchive(zip);
  ASSERT_EQ(entries.size(), 4u);
  EXPECT_EQ(entries.at("tour.json"), kText);
  EXPECT_EQ(entries.at("images/k000000_full.jpg"), kImage);
  EXPECT_EQ(entries.at("empty.txt"), "");
  EXPECT_EQ(entries.at("media/clip.mp4"), kImage.substr(0, 5000));
  EXPECT_EQ(w.files(), (std::vector<std::string>{"tour.json", "images/k000000_full.jpg", "empty.txt",
                                                 "media/clip.mp4"}));
  // Deflated text: the archive is smaller than its contents by about the text's size.
  EXPECT_LT(bytes, kImage.size() + 5000 + kText.size() / 4);
  fs::remove_all(dir);
}

TEST(PackageWriter, PythonReadsMethodsAndContents) {
  const fs::path dir = test_dir("python");
  const fs::path zip = dir / "tour.zip";
  PackageWriter w(zip.string());
  w.add("tour.json", kText);
  w.add("player.js", kText);
  w.add("images/k000000_full.jpg", kImage);
  w.add("media/poster.png", kImage.substr(0, 1000));
  w.commit();
  std::ofstream(dir / "text.bin", std::ios::binary) << kText;
  std::ofstream(dir / "image.bin", std::ios::binary) << kImage;
  EXPECT_TRUE(
      python_accepts("import sys, zipfile\n"
                     "z = zipfile.ZipFile(sys.argv[1])\n"
                     "assert z.testzip() is None\n"
                     "i = {e.filename: e for e in z.infolist()}\n"
                     "assert i['tour.json'].compress_type == zipfile.ZIP_DEFLATED\n"
                     "assert i['player.js'].compress_type == zipfile.ZIP_DEFLATED\n"
                     "assert i['images/k000000_full.jpg'].compress_type == zipfile.ZIP_STORED\n"
                     "assert i['media/poster.png'].compress_type == zipfile.ZIP_STORED\n"
                     "assert i['tour.json'].compress_size < i['tour.json'].file_size / 4\n"
                     "d = '" +
                         dir.string() +
                         "/'\n"
                         "assert z.read('tour.json') == open(d + 'text.bin', 'rb').read()\n"
                         "assert z.read('images/k000000_full.jpg') == open(d + 'image.bin', 'rb').read()\n",
                     zip));
  const std::string unzip = "unzip -tq '" + zip.string() + "' >/dev/null";
  EXPECT_EQ(std::system(unzip.c_str()), 0);
  fs::remove_all(dir);
}

// ZIP64 forced on small entries: each local header carries the ZIP64 extra field (id 0x0001, sizes
// 0xFFFFFFFF in the header proper, version 4.5 to extract), and python reads the archive whole.
const char* kLocalZip64Check =
    "import struct, sys, zipfile\n"
    "z = zipfile.ZipFile(sys.argv[1])\n"
    "assert z.testzip() is None\n"
    "raw = open(sys.argv[1], 'rb').read()\n"
    "def ids(extra):\n"
    "    out, at = [], 0\n"
    "    while at + 4 <= len(extra):\n"
    "        k, n = struct.unpack('<HH', extra[at:at + 4]); out.append(k); at += 4 + n\n"
    "    return out\n"
    "zip64 = []\n"
    "for e in z.infolist():\n"
    "    sig, version, _, _, _, _, _, csize, usize, nlen, elen = struct.unpack('<IHHHHHIIIHH', "
    "raw[e.header_offset:e.header_offset + 30])\n"
    "    assert sig == 0x04034b50, hex(sig)\n"
    "    extra = raw[e.header_offset + 30 + nlen:e.header_offset + 30 + nlen + elen]\n"
    "    zip64.append(1 in ids(extra) and version >= 45 and usize == 0xFFFFFFFF)\n"
    "print('zip64 local headers:', zip64)\n"
    "sys.exit(0 if (all(zip64) if sys.argv[2] == 'forced' else not any(zip64)) else 1)\n";

bool zip64_check(const fs::path& zip, const std::string& expect) {
  const fs::path file = zip.string() + ".zip64.py";
  std::ofstream(file) << kLocalZip64Check;
  const std::string cmd = "/usr/bin/python3 '" + file.string() + "' '" + zip.string() + "' " + expect;
  return std::system(cmd.c_str()) == 0;
}

TEST(PackageWriter, Zip64RecordsArePythonReadable) {
  const fs::path dir = test_dir("zip64");
  const fs::path zip = dir / "tour.zip";
  PackageWriterOptions options;
  options.force_zip64 = true;
  PackageWriter w(zip.string(), options);
  w.add("tour.json", kText);
  w.add("images/k000000_full.jpg", kImage);
  w.commit();
  EXPECT_TRUE(zip64_check(zip, "forced"));
  const auto entries = read_with_libarchive(zip);
  EXPECT_EQ(entries.at("images/k000000_full.jpg"), kImage);
  EXPECT_EQ(entries.at("tour.json"), kText);
  // The same data without forcing: no ZIP64 field is needed, none is written.
  const fs::path plain = dir / "plain.zip";
  PackageWriter p(plain.string());
  p.add("images/k000000_full.jpg", kImage);
  p.commit();
  EXPECT_TRUE(zip64_check(plain, "plain"));
  fs::remove_all(dir);
}

TEST(PackageWriter, UnsafeAndDuplicateNamesAreRefused) {
  const fs::path dir = test_dir("unsafe");
  for (const std::string out : {"tour.zip", "folder"}) {
    PackageWriter w((dir / out).string());
    w.add("tour.json", "{}");
    for (const char* bad : {"../escape.txt", "/etc/passwd", "a\\b", "images//x.jpg", "C:evil"}) {
      try {
        w.add(bad, "x");
        ADD_FAILURE() << bad;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(out), std::string::npos) << e.what();
      }
    }
    EXPECT_THROW(w.add("tour.json", "again"), Error);
    w.commit();
  }
  EXPECT_FALSE(fs::exists(dir.parent_path() / "escape.txt"));
  EXPECT_EQ(read_with_libarchive(dir / "tour.zip").size(), 1u);
  EXPECT_EQ(read_file(dir / "folder" / "tour.json"), "{}");
  EXPECT_EQ(
      std::distance(fs::recursive_directory_iterator(dir / "folder"), fs::recursive_directory_iterator{}), 1);
  fs::remove_all(dir);
}

// A writer dropped before commit() (an error or a cancel mid-way): no new file, no temporary one, and the
// previous package byte for byte.
TEST(PackageWriter, UnfinishedPackageKeepsThePreviousOne) {
  const fs::path dir = test_dir("unfinished");
  for (const std::string out : {"tour.zip", "folder"}) {
    const fs::path target = dir / out;
    {
      PackageWriter first(target.string());
      first.add("tour.json", "old");
      first.commit();
    }
    const std::string before = fs::is_directory(target) ? read_file(target / "tour.json") : read_file(target);
    {
      PackageWriter second(target.string());
      second.add("tour.json", "new");
      second.add("images/k000000_full.jpg", kImage);
      // destroyed here, uncommitted
    }
    EXPECT_EQ(fs::is_directory(target) ? read_file(target / "tour.json") : read_file(target), before) << out;
    {
      PackageWriter never((dir / ("never_" + out)).string());
      never.add("tour.json", "x");
    }
    EXPECT_FALSE(fs::exists(dir / ("never_" + out))) << out;
  }
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"folder", "tour.zip"}));
  // A committed replacement replaces.
  PackageWriter third((dir / "folder").string());
  third.add("tour.json", "new");
  third.commit();
  EXPECT_EQ(read_file(dir / "folder" / "tour.json"), "new");
  fs::remove_all(dir);
}

// What a killed export left (its process gone: pid 2^22 + 1 is above Linux's pid_max): the temporary package
// removed; a folder stepped aside between the two renames put back.
TEST(PackageWriter, LeftoversOfAKilledExportAreCleanedUp) {
  const fs::path dir = test_dir("killed");
  const std::string dead = std::to_string((1 << 22) + 1);
  std::ofstream(dir / (".tour.zip.partial" + dead)) << "half a zip";
  fs::create_directories(dir / (".folder.old" + dead));
  std::ofstream(dir / (".folder.old" + dead) / "tour.json") << "previous";
  fs::create_directories(dir / (".folder.partial" + dead));
  const std::string alive = std::to_string(::getpid() == 1 ? 2 : 1);  // init: always there
  std::ofstream(dir / (".tour.zip.partial" + alive)) << "another export's";
  {
    PackageWriter zip((dir / "tour.zip").string());
    PackageWriter folder((dir / "folder").string());
  }
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{".tour.zip.partial" + alive, "folder"}));
  EXPECT_EQ(read_file(dir / "folder" / "tour.json"), "previous");
  fs::remove_all(dir);
}

TEST(PackageWriter, ClearErrors) {
  try {
    PackageWriter w("/proc/no/such/place/tour.zip");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/no/such/place/tour.zip"), std::string::npos) << e.what();
  }
  PackageWriterOptions options;
  options.deflate_level = 0;
  try {
    options.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("deflate_level"), std::string::npos) << e.what();
  }
  const fs::path dir = test_dir("errors");
  PackageWriter w((dir / "tour.zip").string());
  EXPECT_THROW(w.add_file("media/x.mp4", (dir / "absent.mp4").string()), Error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plenopath
