#pragma once
/// \file render.h
/// Headless rendering of the viewer's scene to PNG with mrpt::opengl::CFBORender (an EGL offscreen
/// context: no X server needed; MRPT-NOTES.md). Files are written atomically.

#include <memory>
#include <string>

#include "roadslam/viewer/replay.h"

namespace mrpt::opengl {
class COpenGLScene;
}

namespace roadslam::viewer {

class PngRenderer {
 public:
  PngRenderer(int width_px, int height_px);
  ~PngRenderer();
  /// Renders \p scene seen from \p view into \p png_path (written atomically); throws naming the
  /// path on error.
  void render(const mrpt::opengl::COpenGLScene& scene, const CameraView& view, const std::string& png_path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The scene of \p replay at its current time, rendered to \p png_path.
void renderCurrent(Replay& replay, PngRenderer& renderer, const std::string& png_path);

/// One PNG per \p every observations holding points, from the first to the last, into
/// \p dir/NNNNNN.png (NNNNNN: the observation index); returns the number written.
std::size_t renderSequence(Replay& replay, PngRenderer& renderer, const std::string& dir, std::size_t every);

}  // namespace roadslam::viewer
