#include "roadslam/viewer/render.h"

#include <mrpt/img/CImage.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::viewer {

struct PngRenderer::Impl {
  mrpt::opengl::CFBORender fbo;
  Impl(int w, int h) : fbo(unsigned(w), unsigned(h)) {}
};

PngRenderer::PngRenderer(int w, int h) : impl_(std::make_unique<Impl>(w, h)) {}
PngRenderer::~PngRenderer() = default;

void PngRenderer::render(const mrpt::opengl::COpenGLScene& scene, const CameraView& view,
                         const std::string& png_path) {
  auto& cam = impl_->fbo.getCamera(scene);
  cam.setProjectiveModel(true);
  cam.setPointingAt(float(view.target.x()), float(view.target.y()), float(view.target.z()));
  cam.setAzimuthDegrees(float(view.azimuth_deg));
  cam.setElevationDegrees(float(view.elevation_deg));
  cam.setZoomDistance(float(view.distance_m));
  mrpt::img::CImage img;
  impl_->fbo.render_RGB(scene, img);
  const std::string tmp = tempPathFor(png_path) + ".png";  // the extension selects the encoder
  if (!img.saveToFile(tmp)) throw std::runtime_error("cannot write '" + png_path + "'");
  commitTempFile(tmp, png_path);
}

void renderCurrent(Replay& replay, PngRenderer& renderer, const std::string& png_path) {
  mrpt::opengl::COpenGLScene scene;
  const CameraView view = buildScene(replay.model(), replay.state(), replay.options(), scene);
  renderer.render(scene, view, png_path);
}

std::size_t renderSequence(Replay& replay, PngRenderer& renderer, const std::string& dir, std::size_t every) {
  std::filesystem::create_directories(dir);
  replay.seek(replay.model().startTime());
  std::size_t written = 0, seen = 0;
  std::optional<std::size_t> last;
  for (;;) {
    const auto cur = replay.currentObservation();
    if (!cur || cur == last) break;
    last = cur;
    if (seen++ % std::max<std::size_t>(every, 1) == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "/%06zu.png", *cur);
      renderCurrent(replay, renderer, dir + name);
      ++written;
    }
    replay.stepSweep(+1);
  }
  return written;
}

}  // namespace roadslam::viewer
