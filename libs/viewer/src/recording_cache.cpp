#include "roadslam/viewer/recording_cache.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace roadslam::viewer {
namespace fs = std::filesystem;

namespace {
constexpr std::size_t kHeadBytes = 64 * 1024;  // content hashed of a file's head [bytes]

/// FNV-1a, 64 bits (Fowler, Noll, Vo): a fast hash that is the same on every run and machine.
struct Fnv1a {
  uint64_t h = 14695981039346656037ull;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void text(const std::string& s) { bytes(s.c_str(), s.size() + 1); }  // the NUL ends it: "ab","c" != "a","bc"
  void number(uint64_t v) { bytes(&v, sizeof v); }
};

struct Stat {
  uint64_t size = 0;
  int64_t mtime_ns = 0;
  bool dir = false;
};

Stat statOf(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error("cannot read '" + path + "': " + std::strerror(errno));
  return {uint64_t(st.st_size), int64_t(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec, S_ISDIR(st.st_mode)};
}

/// Size, modification time and the first kHeadBytes of a file.
void hashFile(Fnv1a& h, const std::string& path) {
  const Stat s = statOf(path);
  h.number(s.size);
  h.number(uint64_t(s.mtime_ns));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot read '" + path + "'");
  std::vector<char> head(kHeadBytes);
  f.read(head.data(), std::streamsize(head.size()));
  h.bytes(head.data(), std::size_t(f.gcount()));
}

/// Each regular file's name, size and modification time (in name order), the times.txt one level up,
/// and the head of the first file.
void hashFolder(Fnv1a& h, const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const auto& n : names) {
    const Stat s = statOf((dir / n).string());
    h.text(n);
    h.number(s.size);
    h.number(uint64_t(s.mtime_ns));
  }
  const fs::path up = dir.parent_path() / "times.txt";  // a KITTI odometry sequence: 00/{times.txt,velodyne/}
  std::error_code ec;
  if (fs::is_regular_file(up, ec)) {
    h.text("../times.txt");
    hashFile(h, up.string());
  }
  if (!names.empty()) hashFile(h, (dir / names.front()).string());
}
}  // namespace

std::string userCacheFolder() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && xdg[0] == '/') return (fs::path(xdg) / "roadslam").string();
  const char* home = std::getenv("HOME");
  if (home && *home) return (fs::path(home) / ".cache" / "roadslam").string();
  return {};
}

std::string identityKey(const std::string& path) {
  std::error_code ec;
  const fs::path canon = fs::canonical(path, ec);
  if (ec) throw std::runtime_error("cannot read '" + path + "': " + ec.message());
  Fnv1a h;
  h.text(canon.string());
  if (statOf(canon.string()).dir) hashFolder(h, canon);
  else hashFile(h, canon.string());
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.h));
  return hex;
}

std::string cacheFileName(const std::string& path, const std::string& ext) {
  std::error_code ec;
  const fs::path canon = fs::canonical(path, ec);
  std::string stem = (ec ? fs::path(path) : canon).stem().string();
  if (stem.empty()) stem = "recording";
  return stem + "-" + identityKey(path) + ext;
}

RecordingCache::RecordingCache(bool persistent) {
  if (!persistent) return;
  const std::string dir = userCacheFolder();
  const std::string then = ": conversions go into a temporary folder removed at exit, and no index is kept";
  if (dir.empty()) {
    note_ = "no cache folder ($XDG_CACHE_HOME and $HOME are not set)" + then;
    return;
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    note_ = "cannot create the cache folder '" + dir + "' (" + ec.message() + ")" + then;
    return;
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    note_ = "cannot write the cache folder '" + dir + "' (" + std::strerror(errno) + ")" + then;
    return;
  }
  persistent_ = true;
  folder_ = dir;
}

RecordingCache::~RecordingCache() {
  std::error_code ec;
  if (!private_.empty()) fs::remove_all(private_, ec);
}

std::string RecordingCache::fileFor(const std::string& input, const std::string& ext) {
  const std::string name = cacheFileName(input, ext);
  if (persistent_) return (fs::path(folder_) / name).string();
  if (private_.empty()) {
    std::string tmpl = (fs::temp_directory_path() / "roadslam-view-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary folder '" + tmpl + "': " + std::strerror(errno));
    private_ = tmpl;
  }
  return (fs::path(private_) / name).string();
}

void RecordingCache::configureIndex(rawlog::RawlogIndexOptions& opt) const {
  if (!persistent_) {
    opt.write_cache = false;
    return;
  }
  const std::string folder = folder_;  // by value: the options are copied onto the indexing threads
  opt.cache_path = [folder](const std::string& rawlog) {
    if (fs::path(rawlog).parent_path() == fs::path(folder)) return rawlog::RawlogIndex::sidecarPath(rawlog);  // a conversion
    return (fs::path(folder) / cacheFileName(rawlog, ".idx")).string();
  };
}

}  // namespace roadslam::viewer
