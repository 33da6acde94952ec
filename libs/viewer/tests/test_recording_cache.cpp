// RecordingCache: where roadslam-view keeps conversions and indexes (the user's cache folder, by the
// XDG base directory rules), and the identity key that tells two inputs of the same name apart.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include "roadslam/viewer/recording_cache.h"

namespace fs = std::filesystem;
using roadslam::viewer::cacheFileName;
using roadslam::viewer::identityKey;
using roadslam::viewer::RecordingCache;
using roadslam::viewer::userCacheFolder;

namespace {

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("roadslam_recording_cache_" + std::to_string(getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

/// Sets an environment variable for the scope (unset: nullptr), restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value) setenv(name, value, 1);
    else unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_) setenv(name_, old_.c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST(RecordingCache, UserCacheFolderFollowsTheXdgRules) {
  {
    ScopedEnv xdg("XDG_CACHE_HOME", "/srv/cache"), home("HOME", "/home/ana");
    EXPECT_EQ(userCacheFolder(), "/srv/cache/roadslam");
  }
  {
    ScopedEnv xdg("XDG_CACHE_HOME", "relative/cache"), home("HOME", "/home/ana");  // the spec ignores a relative path
    EXPECT_EQ(userCacheFolder(), "/home/ana/.cache/roadslam");
  }
  {
    ScopedEnv xdg("XDG_CACHE_HOME", nullptr), home("HOME", "/home/ana");
    EXPECT_EQ(userCacheFolder(), "/home/ana/.cache/roadslam");
  }
  {
    ScopedEnv xdg("XDG_CACHE_HOME", nullptr), home("HOME", nullptr);
    EXPECT_EQ(userCacheFolder(), "");
  }
}

// Two files of the same name in two folders, a file changed in place (same size, new content or a
// new time), and a folder whose file list changes: each gets a key of its own.
TEST(RecordingCache, IdentityKeyTellsInputsOfTheSameNameApart) {
  const fs::path d = freshDir("identity");
  write(d / "a" / "velodyne.pcap", std::string(100000, 'x'));
  write(d / "b" / "velodyne.pcap", std::string(100000, 'x'));  // the same bytes elsewhere
  const std::string a = (d / "a" / "velodyne.pcap").string(), b = (d / "b" / "velodyne.pcap").string();
  const std::regex name(R"(velodyne-[0-9a-f]{16}\.rawlog)");
  EXPECT_TRUE(std::regex_match(cacheFileName(a, ".rawlog"), name)) << cacheFileName(a, ".rawlog");
  EXPECT_NE(identityKey(a), identityKey(b));
  EXPECT_EQ(identityKey(a), identityKey((d / "a" / ".." / "a" / "velodyne.pcap").string())) << "the canonical path";

  const std::string before = identityKey(a);
  const auto mtime = fs::last_write_time(a);
  {
    std::fstream f(a, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(10);
    f.put('y');  // new content at the head, same size
  }
  fs::last_write_time(a, mtime);  // and the same time: the content alone tells
  EXPECT_NE(identityKey(a), before);
  const std::string after_edit = identityKey(a);
  fs::last_write_time(a, mtime + std::chrono::seconds(1));
  EXPECT_NE(identityKey(a), after_edit) << "a new modification time";

  write(d / "kitti" / "000000.bin", std::string(64, '\1'));
  const std::string folder = (d / "kitti").string(), k0 = identityKey(folder);
  EXPECT_EQ(cacheFileName(folder, ".rawlog"), "kitti-" + k0 + ".rawlog");
  write(d / "kitti" / "000001.bin", std::string(64, '\1'));
  const std::string k1 = identityKey(folder);
  EXPECT_NE(k1, k0);
  write(d / "times.txt", "0.0\n0.1\n");  // a KITTI odometry sequence's times, one level up
  EXPECT_NE(identityKey(folder), k1);
  EXPECT_THROW(identityKey((d / "nope.pcap").string()), std::runtime_error);
}

TEST(RecordingCache, UsesTheUserCacheFolderAndPutsIndexesThere) {
  const fs::path d = freshDir("user");
  ScopedEnv xdg("XDG_CACHE_HOME", d.c_str());
  write(d / "in" / "drive.rawlog", "x");
  RecordingCache cache(true);
  EXPECT_TRUE(cache.persistent());
  EXPECT_EQ(cache.note(), "");
  const std::string out = cache.fileFor((d / "in" / "drive.rawlog").string(), ".rawlog");
  EXPECT_EQ(fs::path(out).parent_path(), d / "roadslam");
  roadslam::rawlog::RawlogIndexOptions opt;
  cache.configureIndex(opt);
  ASSERT_TRUE(opt.cache_path);
  EXPECT_EQ(opt.cache_path((d / "in" / "drive.rawlog").string()),
            (d / "roadslam" / cacheFileName((d / "in" / "drive.rawlog").string(), ".idx")).string());
  write(out, "y");  // a conversion in the cache: its index beside it
  EXPECT_EQ(opt.cache_path(out), out + ".idx");
}

// A cache folder that cannot be made: a private temporary folder (mode 0700), removed with the
// cache, and no index kept. --no-index-cache asks for that.
TEST(RecordingCache, WithoutAUsableFolderConvertsIntoAPrivateFolderRemovedAtTheEnd) {
  const fs::path d = freshDir("unusable");
  write(d / "a-file", "x");
  write(d / "in.pcap", "x");
  ScopedEnv xdg("XDG_CACHE_HOME", (d / "a-file").c_str());  // roadslam/ cannot be made under a file
  fs::path made;
  {
    RecordingCache cache(true);
    EXPECT_FALSE(cache.persistent());
    EXPECT_NE(cache.note().find("cannot create the cache folder '" + (d / "a-file" / "roadslam").string() + "'"),
              std::string::npos) << cache.note();
    EXPECT_NE(cache.note().find("removed at exit"), std::string::npos) << cache.note();
    const std::string out = cache.fileFor((d / "in.pcap").string(), ".rawlog");
    made = fs::path(out).parent_path();
    EXPECT_TRUE(fs::is_directory(made));
    EXPECT_EQ(fs::status(made).permissions() & fs::perms::all, fs::perms::owner_all);
    EXPECT_EQ(made.parent_path(), fs::temp_directory_path());
    roadslam::rawlog::RawlogIndexOptions opt;
    cache.configureIndex(opt);
    EXPECT_FALSE(opt.write_cache);
    EXPECT_FALSE(opt.cache_path);
  }
  EXPECT_FALSE(fs::exists(made));
  RecordingCache asked_for_none(false);
  EXPECT_FALSE(asked_for_none.persistent());
  EXPECT_EQ(asked_for_none.note(), "");
}
