// RawlogIndex: the sidecar round trip and its staleness, random access equal to a sequential read
// (gzip with many access points, multi-member gzip, plain files), truncated and corrupt files
// indexed up to the damage, unknown classes listed and skipped.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "roadslam/rawlog/background_rawlog_index.h"
#include "roadslam/rawlog/mrpt_stamp.h"
#include "roadslam/rawlog/rawlog_index.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "roadslam/sources/rawlog_source.h"
#include "test_packets.h"

using namespace roadslam::sources;
using namespace roadslam::rawlog;
using namespace roadslam::sources::test_support;
namespace fs = std::filesystem;

namespace {

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_rawlog_index_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

constexpr double kT0 = 1453364282.0;

// \p sweeps sweeps of \p packets packets with a GPS record after every one: 2 * sweeps observations.
void writeRecording(const fs::path& path, int sweeps, int packets, uint32_t seed = 7, uint32_t first_packet = 0) {
  RawlogWriter w(path.string(), RawlogWriter::Params{});
  uint32_t k = first_packet;
  for (int s = 0; s < sweeps; ++s) {
    std::vector<roadslam::velodyne::RawPacket> sweep;
    for (int i = 0; i < packets; ++i, ++k) {
      roadslam::velodyne::RawPacket p;
      const uint32_t t_us = uint32_t(k * 1327);
      p.stamp_s = kT0 + t_us * 1e-6;
      p.payload = makeDataPacket(t_us, uint16_t(i * 36000 / packets), seed + k);
      sweep.push_back(p);
    }
    w.writeSweep(sweep);
    roadslam::velodyne::RawPacket g;
    g.stamp_s = sweep.back().stamp_s;
    g.payload = makePositionPacket(k * 1327, kAlmeriaRmc);
    EXPECT_TRUE(w.writePosition(g));
  }
  w.close();
}

std::string bytesOf(const mrpt::serialization::CSerializable& o) {
  mrpt::io::CMemoryStream m;
  mrpt::serialization::archiveFrom(m) << o;
  return std::string(static_cast<const char*>(m.getRawBufferData()), m.getTotalBytesCount());
}

// Every observation read front to back with MRPT's own gzip stream.
std::vector<std::string> sequentialRead(const fs::path& path) {
  std::vector<std::string> out;
  mrpt::io::CFileGZInputStream in(path.string());
  for (;;) {
    try {
      auto o = mrpt::serialization::archiveFrom(in).ReadObject();
      out.push_back(bytesOf(*o));
    } catch (const std::exception&) {
      break;
    }
  }
  return out;
}

RawlogIndexOptions smallSpan() {
  RawlogIndexOptions o;
  o.span_bytes = 200 * 1024;  // many access points on a few MB
  return o;
}

}  // namespace

TEST(RawlogIndex, IndexesEveryObservationWithTimeLabelAndClass) {
  const fs::path path = tempDir() / "basic.rawlog";
  writeRecording(path, 5, 20);
  fs::remove(RawlogIndex::sidecarPath(path.string()));
  const auto idx = RawlogIndex::open(path.string());
  ASSERT_EQ(idx->size(), 10u);
  EXPECT_TRUE(idx->complete()) << idx->stopMessage();
  EXPECT_TRUE(idx->gzip());
  EXPECT_FALSE(idx->openInfo().from_cache);
  EXPECT_TRUE(idx->openInfo().cache_written);
  for (std::size_t i = 0; i < idx->size(); ++i) {
    EXPECT_EQ(idx->className(i), i % 2 ? "CObservationGPS" : "CObservationVelodyneScan");
    EXPECT_EQ(idx->label(i), i % 2 ? "GPS" : "VELODYNE");
    if (i > 0) {
      EXPECT_GT(idx->entry(i).offset, idx->entry(i - 1).offset);
      EXPECT_GE(idx->entry(i).stamp_s, idx->entry(i - 1).stamp_s);
    }
  }
  EXPECT_EQ(idx->entry(0).offset, 0u);
  EXPECT_NEAR(idx->firstStamp(), kT0, 1e-6);
  EXPECT_EQ(idx->entry(1).offset + idx->entry(1).size, idx->entry(2).offset);
  EXPECT_EQ(idx->entry(9).offset + idx->entry(9).size, idx->uncompressedBytes());
  // time lookups: the last observation at or before the time
  EXPECT_EQ(*idx->findAtTime(kT0 - 10), 0u);
  EXPECT_EQ(*idx->findAtTime(idx->entry(4).stamp_s + 1e-4), 4u);
  EXPECT_EQ(*idx->findAtTime(1e12), 9u);
  EXPECT_TRUE(idx->unknownClasses().empty());
}

TEST(RawlogIndex, SidecarRoundTripAndStaleness) {
  const fs::path path = tempDir() / "cache.rawlog";
  writeRecording(path, 6, 30);
  const std::string side = RawlogIndex::sidecarPath(path.string());
  fs::remove(side);
  const auto built = RawlogIndex::open(path.string(), smallSpan());
  ASSERT_TRUE(fs::exists(side));
  const auto cached = RawlogIndex::open(path.string(), smallSpan());
  EXPECT_TRUE(cached->openInfo().from_cache) << cached->openInfo().cache_note;
  ASSERT_EQ(cached->size(), built->size());
  for (std::size_t i = 0; i < built->size(); ++i) {
    EXPECT_EQ(cached->entry(i).offset, built->entry(i).offset);
    EXPECT_EQ(cached->entry(i).size, built->entry(i).size);
    EXPECT_EQ(cached->entry(i).stamp_s, built->entry(i).stamp_s);
    EXPECT_EQ(cached->label(i), built->label(i));
    EXPECT_EQ(cached->className(i), built->className(i));
    EXPECT_EQ(bytesOf(*cached->load(i)), bytesOf(*built->load(i)));
  }

  // the rawlog rewritten (other size and time): the sidecar is stale and rebuilt
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  writeRecording(path, 4, 30, 99);
  const auto stale = RawlogIndex::open(path.string(), smallSpan());
  EXPECT_FALSE(stale->openInfo().from_cache);
  EXPECT_NE(stale->openInfo().cache_note.find("stale"), std::string::npos) << stale->openInfo().cache_note;
  EXPECT_EQ(stale->size(), 8u);
  EXPECT_TRUE(RawlogIndex::open(path.string())->openInfo().from_cache);

  // a damaged sidecar is rebuilt, never trusted
  {
    std::string bytes;
    {
      std::ifstream f(side, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(f), {});
    }
    std::ofstream f(side, std::ios::binary | std::ios::trunc);
    f << bytes.substr(0, bytes.size() / 2);
  }
  const auto rebuilt = RawlogIndex::open(path.string());
  EXPECT_FALSE(rebuilt->openInfo().from_cache);
  EXPECT_NE(rebuilt->openInfo().cache_note.find("unreadable"), std::string::npos) << rebuilt->openInfo().cache_note;
  EXPECT_EQ(rebuilt->size(), 8u);
}

TEST(RawlogIndex, RandomAccessEqualsSequentialRead) {
  const fs::path path = tempDir() / "random.rawlog";
  writeRecording(path, 40, 76);  // ~3.7 MB uncompressed: ~18 access points
  fs::remove(RawlogIndex::sidecarPath(path.string()));
  const auto seq = sequentialRead(path);
  for (int pass = 0; pass < 2; ++pass) {  // built, then from the sidecar
    const auto idx = RawlogIndex::open(path.string(), smallSpan());
    EXPECT_EQ(idx->openInfo().from_cache, pass == 1);
    ASSERT_EQ(idx->size(), seq.size());
    EXPECT_GE(idx->accessPoints(), 10u);
    std::vector<std::size_t> order(seq.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(42 + pass));
    for (const auto i : order) ASSERT_EQ(bytesOf(*idx->load(i)), seq[i]) << "observation " << i;
  }
}

TEST(RawlogIndex, PlainAndMultiMemberGzipFiles) {
  const fs::path dir = tempDir();
  writeRecording(dir / "a.rawlog", 8, 40, 1);
  writeRecording(dir / "b.rawlog", 8, 40, 2);
  const auto a = sequentialRead(dir / "a.rawlog"), b = sequentialRead(dir / "b.rawlog");
  {  // two gzip members back to back, as `cat a b` gives
    std::ofstream out(dir / "ab.rawlog", std::ios::binary);
    for (const char* n : {"a.rawlog", "b.rawlog"}) out << std::ifstream(dir / n, std::ios::binary).rdbuf();
  }
  {  // the same observations uncompressed
    mrpt::io::CFileOutputStream out((dir / "plain.rawlog").string());
    for (const auto* part : {&a, &b})
      for (const auto& s : *part) out.Write(s.data(), s.size());
  }
  for (const char* name : {"ab.rawlog", "plain.rawlog"}) {
    const auto idx = RawlogIndex::open((dir / name).string(), smallSpan());
    ASSERT_EQ(idx->size(), a.size() + b.size()) << name << ": " << idx->stopMessage();
    EXPECT_TRUE(idx->complete()) << idx->stopMessage();
    EXPECT_EQ(idx->gzip(), std::string(name) == "ab.rawlog");
    for (std::size_t i = idx->size(); i-- > 0;)
      EXPECT_EQ(bytesOf(*idx->load(i)), i < a.size() ? a[i] : b[i - a.size()]) << name << " " << i;
  }
}

TEST(RawlogIndex, TruncatedFileIsIndexedUpToTheDamage) {
  const fs::path path = tempDir() / "truncated.rawlog";
  writeRecording(path, 20, 76);
  const auto full = sequentialRead(path);
  fs::resize_file(path, fs::file_size(path) * 6 / 10);
  const auto idx = RawlogIndex::open(path.string(), smallSpan());
  EXPECT_FALSE(idx->complete());
  ASSERT_GT(idx->size(), 5u);
  ASSERT_LT(idx->size(), full.size());
  const std::string& m = idx->stopMessage();
  EXPECT_EQ(m.rfind("truncated record at uncompressed byte ", 0), 0u) << m;  // as RawlogPacketSource words it
  EXPECT_NE(m.find("(observation " + std::to_string(idx->size()) + ", compressed byte"), std::string::npos) << m;
  for (std::size_t i = 0; i < idx->size(); ++i) EXPECT_EQ(bytesOf(*idx->load(i)), full[i]);
  // the damage is cached too
  const auto cached = RawlogIndex::open(path.string(), smallSpan());
  EXPECT_TRUE(cached->openInfo().from_cache);
  EXPECT_EQ(cached->stopMessage(), m);
}

// The replay (RawlogPacketSource, which roadslam-map reads) and the index (which roadslam-view
// reads) name the place of a cut rawlog in the same words: the index's message begins with the replay's.
TEST(RawlogIndex, TruncationIsNamedAsTheReplayNamesIt) {
  const fs::path path = tempDir() / "cut_same_words.rawlog";
  writeRecording(path, 20, 76);
  fs::resize_file(path, fs::file_size(path) / 2);
  RawlogPacketSource replay(path.string());
  while (replay.next()) {
  }
  const auto idx = RawlogIndex::open(path.string(), smallSpan());
  const std::string replay_place = replay.errorMessage();
  ASSERT_EQ(replay_place.rfind(path.string() + ": truncated record at uncompressed byte ", 0), 0u) << replay_place;
  EXPECT_EQ((path.string() + ": " + idx->stopMessage()).rfind(replay_place + " (observation ", 0), 0u)
      << replay_place << "\nvs " << idx->stopMessage();
}

TEST(RawlogIndex, CorruptCompressedDataStopsThereWithTheByte) {
  const fs::path path = tempDir() / "corrupt.rawlog";
  writeRecording(path, 20, 76);
  const auto full = sequentialRead(path);
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(fs::file_size(path) / 2));
    const std::string junk(4096, '\x5a');
    f.write(junk.data(), std::streamsize(junk.size()));
  }
  const auto idx = RawlogIndex::open(path.string(), smallSpan());
  EXPECT_FALSE(idx->complete());
  EXPECT_LT(idx->size(), full.size());
  EXPECT_NE(idx->stopMessage().find(" record at uncompressed byte "), std::string::npos) << idx->stopMessage();
  EXPECT_NE(idx->stopMessage().find("(observation " + std::to_string(idx->size())), std::string::npos) << idx->stopMessage();
  for (std::size_t i = 0; i < idx->size(); ++i) EXPECT_EQ(bytesOf(*idx->load(i)), full[i]);
}

TEST(RawlogIndex, UnknownClassesAreListedAndSkipped) {
  const fs::path path = tempDir() / "unknown.rawlog";
  writeRecording(path, 3, 10);
  const auto obs = sequentialRead(path);
  {  // MRPT's object framing (0x80|name length, name, version, data, 0x88) of a class nobody registered
    mrpt::io::CFileGZOutputStream out(path.string() + ".tmp");
    const std::string name = "CObservationFromTheFuture";
    std::string rec(1, char(0x80 | name.size()));
    rec += name;
    rec += char(0);
    for (int i = 0; i < 300; ++i) rec += char(i * 7);
    rec += char(0x88);
    for (std::size_t i = 0; i < obs.size(); ++i) {
      out.Write(obs[i].data(), obs[i].size());
      if (i == 1 || i == 3) out.Write(rec.data(), rec.size());
    }
  }
  fs::rename(path.string() + ".tmp", path);
  const auto idx = RawlogIndex::open(path.string());
  ASSERT_EQ(idx->size(), obs.size() + 2) << idx->stopMessage();
  EXPECT_TRUE(idx->complete()) << idx->stopMessage();
  const auto unknown = idx->unknownClasses();
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_EQ(unknown[0].first, "CObservationFromTheFuture");
  EXPECT_EQ(unknown[0].second, 2u);
  EXPECT_FALSE(idx->entry(2).known);
  EXPECT_EQ(idx->entry(2).size, 1 + 25 + 1 + 300 + 1u);
  EXPECT_THROW(idx->load(2), std::runtime_error);
  std::size_t k = 0;
  for (std::size_t i = 0; i < idx->size(); ++i)
    if (idx->entry(i).known) {
      EXPECT_EQ(bytesOf(*idx->load(i)), obs[k++]);
    }
  EXPECT_EQ(k, obs.size());
}

// A program that must not write beside its input (roadslam-view) keeps the index where cache_path
// says; a fresh sidecar beside the rawlog (roadslam-grab's) is still read, and never written.
TEST(RawlogIndex, CachePathKeepsTheIndexAwayFromTheRawlog) {
  const fs::path dir = tempDir() / "cache_path";
  fs::remove_all(dir);
  fs::create_directories(dir / "cache");
  const fs::path path = dir / "drive.rawlog";
  writeRecording(path, 4, 30);
  RawlogIndexOptions opt = smallSpan();
  opt.cache_path = [&dir](const std::string&) { return (dir / "cache" / "drive.idx").string(); };
  const auto files = RawlogIndex::indexFiles(path.string(), opt);
  EXPECT_EQ(files.write, (dir / "cache" / "drive.idx").string());
  ASSERT_EQ(files.read.size(), 2u);
  EXPECT_EQ(files.read[0], RawlogIndex::sidecarPath(path.string()));

  const auto built = RawlogIndex::open(path.string(), opt);
  EXPECT_TRUE(built->openInfo().cache_written);
  EXPECT_FALSE(fs::exists(RawlogIndex::sidecarPath(path.string()))) << "nothing beside the rawlog";
  EXPECT_TRUE(fs::exists(dir / "cache" / "drive.idx"));
  EXPECT_TRUE(RawlogIndex::open(path.string(), opt)->openInfo().from_cache);
  const auto background = BackgroundRawlogIndex::open(path.string(), opt);
  ASSERT_NE(background->done(), nullptr) << "a fresh cached index opens whole at once";
  EXPECT_EQ(background->size(), built->size());

  // a fresh sidecar beside the rawlog is read first; the cached one is left as it is
  fs::remove(dir / "cache" / "drive.idx");
  RawlogIndex::open(path.string(), smallSpan());  // writes the sidecar, as roadslam-grab would
  const auto beside = RawlogIndex::open(path.string(), opt);
  EXPECT_TRUE(beside->openInfo().from_cache);
  EXPECT_FALSE(fs::exists(dir / "cache" / "drive.idx"));

  // a stale sidecar beside it is not rewritten: the index is built into the cache
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  writeRecording(path, 3, 30, 99);
  const auto side_bytes = fs::file_size(RawlogIndex::sidecarPath(path.string()));
  const auto rebuilt = RawlogIndex::open(path.string(), opt);
  EXPECT_EQ(rebuilt->size(), 6u);
  EXPECT_TRUE(fs::exists(dir / "cache" / "drive.idx"));
  EXPECT_EQ(fs::file_size(RawlogIndex::sidecarPath(path.string())), side_bytes);
}

// MRPT stamps before 1970 read back negative (mrpt::Clock::toDouble wraps them to ~1.8e12 s): a
// KITTI sweep stamped at its first firing, half a sweep before times.txt's 0.0.
TEST(RawlogIndex, StampsBefore1970ReadBackNegative) {
  const fs::path path = tempDir() / "before1970.rawlog";
  const double stamps[] = {-0.05, 0.05, 0.15};
  {
    mrpt::io::CFileGZOutputStream f(path.string());
    auto ar = mrpt::serialization::archiveFrom(f);
    for (const double t : stamps) {
      mrpt::obs::CObservationGPS g;
      g.timestamp = stampOf(t);
      ar << g;
    }
  }
  RawlogIndexOptions no_cache;
  no_cache.use_cache = no_cache.write_cache = false;
  const auto idx = RawlogIndex::open(path.string(), no_cache);
  ASSERT_EQ(idx->size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(idx->entry(i).stamp_s, stamps[i], 1e-7);
    EXPECT_NEAR(stampSeconds(stampOf(stamps[i])), stamps[i], 1e-7);
  }
  EXPECT_NEAR(idx->lastStamp() - idx->firstStamp(), 0.2, 1e-7);
}

TEST(RawlogIndex, MissingFileIsNamed) {
  try {
    RawlogIndex::open("/nonexistent/x.rawlog");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.rawlog"), std::string::npos);
  }
}

TEST(RawlogIndex, SensoryFramesAndActionsAsMrptCRawlogWritesThem) {
  // The "actions + sensory frames" layout: each observation of a frame is an entry of its own
  // (same record offset, its position in the frame); an action is listed without a time.
  const fs::path path = tempDir() / "sf.rawlog";
  {
    mrpt::obs::CRawlog rawlog;
    for (int f = 0; f < 3; ++f) {
      mrpt::obs::CActionCollection acts;
      rawlog.insert(acts);
      mrpt::obs::CSensoryFrame sf;
      for (int k = 0; k < 2; ++k) {
        auto g = mrpt::obs::CObservationGPS::Create();
        g->sensorLabel = k == 0 ? "GPS_A" : "GPS_B";
        g->timestamp = mrpt::Clock::fromDouble(kT0 + f + 0.25 * k);
        sf.insert(g);
      }
      rawlog.insert(sf);
    }
    ASSERT_TRUE(rawlog.saveToRawLogFile(path.string()));
  }
  const auto idx = RawlogIndex::open(path.string());
  ASSERT_EQ(idx->size(), 9u) << idx->stopMessage();  // per frame: the action, two observations
  EXPECT_TRUE(idx->complete()) << idx->stopMessage();
  EXPECT_EQ(idx->className(0), "CActionCollection");
  EXPECT_FALSE(std::isfinite(idx->entry(0).stamp_s));
  EXPECT_EQ(idx->load(0), nullptr) << "an action is no observation";
  EXPECT_EQ(idx->entry(1).offset, idx->entry(2).offset);
  EXPECT_EQ(idx->entry(2).sub, 1);
  EXPECT_EQ(idx->label(8), "GPS_B");
  const auto o = idx->load(8);
  ASSERT_TRUE(o);
  EXPECT_EQ(o->sensorLabel, "GPS_B");
  EXPECT_NEAR(mrpt::Clock::toDouble(o->timestamp), kT0 + 2.25, 1e-6);
  EXPECT_EQ(*idx->findAtTime(kT0 + 1.3), 5u);
}

// The viewer's way of opening: the index grows on a thread while what is indexed is already
// listed and loaded. Oracles: MRPT's own sequential read, and the index built in one go.
TEST(BackgroundRawlogIndex, GrowsWhileIndexingAndEndsAsTheFullIndex) {
  const fs::path path = tempDir() / "background.rawlog";
  writeRecording(path, 200, 76);  // 400 observations, ~18 MB uncompressed
  const std::string side = RawlogIndex::sidecarPath(path.string());
  fs::remove(side);
  const auto seq = sequentialRead(path);
  auto bg = BackgroundRawlogIndex::open(path.string(), smallSpan());
  std::size_t partial_polls = 0, loads = 0;
  std::mt19937 rng(3);
  while (!bg->done()) {
    bg->poll();
    if (bg->done()) break;
    ASSERT_TRUE(bg->error().empty()) << bg->error();
    EXPECT_LE(bg->progress(), 1.0);
    if (bg->size() == 0) continue;
    ++partial_polls;
    for (int k = 0; k < 3; ++k) {  // what is visible loads as MRPT reads it
      const std::size_t i = std::uniform_int_distribution<std::size_t>(0, bg->size() - 1)(rng);
      ASSERT_EQ(bytesOf(*bg->load(i)), seq[i]) << "observation " << i << " of " << bg->size() << " indexed so far";
      ++loads;
    }
    EXPECT_LE(bg->firstStamp(), bg->lastStamp());
  }
  EXPECT_GT(partial_polls, 0u) << "the index was never seen growing";
  EXPECT_GT(loads, 0u);
  EXPECT_DOUBLE_EQ(bg->progress(), 1.0);
  ASSERT_EQ(bg->size(), seq.size());
  EXPECT_TRUE(fs::exists(side)) << "the finished build writes the sidecar";
  RawlogIndexOptions fresh = smallSpan();
  fresh.use_cache = fresh.write_cache = false;
  const auto full = RawlogIndex::open(path.string(), fresh);
  for (std::size_t i = 0; i < full->size(); ++i) {
    ASSERT_EQ(bg->entry(i).offset, full->entry(i).offset) << i;
    ASSERT_EQ(bg->className(i), full->className(i)) << i;
    ASSERT_EQ(bg->label(i), full->label(i)) << i;
  }
  EXPECT_EQ(bytesOf(*bg->load(seq.size() - 1)), seq.back());

  const auto again = BackgroundRawlogIndex::open(path.string(), smallSpan());
  ASSERT_TRUE(again->done()) << "a fresh sidecar: complete at once";
  EXPECT_TRUE(again->done()->openInfo().from_cache);

  fs::remove(side);
  BackgroundRawlogIndex::open(path.string(), smallSpan()).reset();  // closed while indexing
  EXPECT_FALSE(fs::exists(side)) << "an abandoned build writes no sidecar";
  EXPECT_THROW(BackgroundRawlogIndex::open((tempDir() / "nope.rawlog").string()), std::runtime_error);
}

// A roadslam-grab session folder: segments shown in order as one recording. Oracle: the segments
// concatenated into one multi-member gzip file, indexed as one rawlog.
TEST(RawlogSession, SegmentsReadAsTheirConcatenation) {
  const fs::path dir = tempDir() / "session";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string joined;
  for (int s = 0; s < 3; ++s) {  // grab_000 .. grab_002, times continuing across them
    const fs::path seg = dir / ("grab_00" + std::to_string(s) + ".rawlog");
    writeRecording(seg, 30, 76, 7, uint32_t(s * 30 * 76));
    std::ifstream f(seg, std::ios::binary);
    joined.append(std::istreambuf_iterator<char>(f), {});
  }
  std::ofstream(dir / "notes.txt") << "not a segment\n";
  std::ofstream(dir / "other_000.rawlog") << "another prefix, later in the order\n";
  const auto segments = RawlogSession::segmentsOf(dir.string());
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(fs::path(segments[2]).filename(), "grab_002.rawlog");
  const fs::path all = tempDir() / "session_all.rawlog";
  std::ofstream(all, std::ios::binary) << joined;
  RawlogIndexOptions no_cache;
  no_cache.use_cache = no_cache.write_cache = false;
  const auto one = RawlogIndex::open(all.string(), no_cache);

  auto session = RawlogSession::open(segments, no_cache);
  std::size_t last = 0;
  while (!session->done()) {
    session->poll();
    EXPECT_GE(session->size(), last) << "indices only grow at the end";
    last = session->size();
  }
  ASSERT_EQ(session->size(), one->size());
  EXPECT_DOUBLE_EQ(session->progress(), 1.0);
  EXPECT_DOUBLE_EQ(session->firstStamp(), one->firstStamp());
  EXPECT_DOUBLE_EQ(session->lastStamp(), one->lastStamp());
  for (std::size_t i = 0; i < one->size(); ++i) {
    ASSERT_EQ(session->className(i), one->className(i)) << i;
    ASSERT_EQ(session->label(i), one->label(i)) << i;
    ASSERT_EQ(session->entry(i).stamp_s, one->entry(i).stamp_s) << i;
  }
  const double mid = 0.5 * (one->firstStamp() + one->lastStamp());
  EXPECT_EQ(session->findAtTime(mid), one->findAtTime(mid));
  EXPECT_EQ(session->findInRange(mid - 0.3, mid + 0.3), one->findInRange(mid - 0.3, mid + 0.3));
  std::mt19937 rng(5);
  for (int k = 0; k < 20; ++k) {
    const std::size_t i = std::uniform_int_distribution<std::size_t>(0, one->size() - 1)(rng);
    ASSERT_EQ(bytesOf(*session->load(i)), bytesOf(*one->load(i))) << "observation " << i;
  }
  EXPECT_THROW(RawlogSession::open({}), std::runtime_error);
  EXPECT_TRUE(RawlogSession::segmentsOf((tempDir() / "nope").string()).empty());

  // the jobs' input: the session folder gives the sweeps of the joined file, point for point
  mrpt::config::CConfigFileMemory no_ini;
  auto a = openScanSource(dir.string(), no_ini), b = openScanSource(all.string(), no_ini);
  EXPECT_NE(a->describe().find("(3 segments)"), std::string::npos) << a->describe();
  std::size_t sweeps = 0;
  for (;;) {
    auto sa = a->next(), sb = b->next();
    ASSERT_EQ(sa.has_value(), sb.has_value()) << "sweep " << sweeps;
    if (!sa) break;
    ++sweeps;
    ASSERT_EQ(sa->stamp_s, sb->stamp_s) << "sweep " << sweeps;
    ASSERT_EQ(sa->points.size(), sb->points.size()) << "sweep " << sweeps;
    for (std::size_t k = 0; k < sa->points.size(); k += 97) ASSERT_EQ(sa->points[k].x, sb->points[k].x);
  }
  EXPECT_GE(sweeps, 89u) << "90 sweeps written, the last may be partial";
  EXPECT_TRUE(a->finished());
  EXPECT_EQ(a->stats().packets, b->stats().packets);
  EXPECT_TRUE(a->errorMessage().empty()) << a->errorMessage();
}
