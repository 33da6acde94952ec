#pragma once
/// \file pipeline.h
/// The one orchestrator of the chain: a source of sweeps and a list of stages (stage.h), the pose
/// stage first. next() reads a sweep and hands its frame to every stage in order, timing each one;
/// `roadslam-map`, `roadslam-bounds`, the viewer's live SLAM and the experiment runner all drive
/// this one loop over the stage list that buildStages (stage_factory.h) makes for them.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/pipeline/pose_stage.h"
#include "roadslam/pipeline/stage.h"
#include "roadslam/sources/scan_source.h"

namespace roadslam::pipeline {

/// A job's stages in the order they see a frame; the first is a PoseStage.
using StageList = std::vector<std::unique_ptr<Stage>>;

class Pipeline {
 public:
  /// Throws std::invalid_argument without a source or when the first stage is not a PoseStage.
  Pipeline(std::unique_ptr<sources::ScanSource> source, StageList stages);
  ~Pipeline();

  /// The next sweep through every stage; nullopt at the end of the source (or, live, when no sweep
  /// came within the source's timeout: source().finished() tells them apart). Per-sweep problems come
  /// back in the frame (no pose, a failed registration); only a broken invariant throws.
  std::optional<PipelineFrame> next();

  /// Every stage finishes the work it holds back (Stage::finish); next() does it at the end of the
  /// source, a job that stops early calls it.
  void finish();

  sources::ScanSource& source() { return *source_; }
  const sources::ScanSource& source() const { return *source_; }
  PoseStage& poses() { return *poses_; }
  /// The first stage of type T, or nullptr.
  template <class T>
  T* find() const {
    for (const auto& s : stages_)
      if (auto* t = dynamic_cast<T*>(s.get())) return t;
    return nullptr;
  }
  const StageTimes& totals() const { return totals_; }  ///< summed over the frames so far
  size_t frames() const { return frames_; }

 private:
  std::unique_ptr<sources::ScanSource> source_;
  StageList stages_;
  PoseStage* poses_ = nullptr;
  bool keep_sweep_ = false;  ///< a stage reads the sweep: the frame carries it out
  StageTimes totals_;
  size_t frames_ = 0;
};

/// Opens the recording \p path (sources::openScanSource) and reads its first sweep: an input that
/// gives none is an error ("input 'X' gives no sweep: <why>") before any output exists. The sweep
/// read is handed out again by the returned source's first next(); its stamp goes to \p first_stamp_s
/// when given (the side inputs are checked against it, common/side_input.h).
std::unique_ptr<sources::ScanSource> openNonEmptySource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& times_path = "", double* first_stamp_s = nullptr);

}  // namespace roadslam::pipeline
