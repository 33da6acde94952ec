#pragma once
/// \file scene.h
/// Builds the viewer's 3D scene (an mrpt::opengl::COpenGLScene) for one instant of the replay: the
/// current sweep coloured by height / intensity / ring / per-point time, the decimated point map, the
/// trajectory so far, ground truth, keyframes, loop-closure edges, the boundaries and the objects
/// (track boxes, ids, velocity arrows: objects_layer.h) of the current sweep, with a follow / top-down / orbit camera. The same scene is shown in the window and rendered
/// headless (render.h), so the pictures in the docs and tests are the window's.

#include <memory>
#include <optional>
#include <string>

#include "roadslam/viewer/model.h"
#include "roadslam/viewer/sweep.h"

namespace mrpt::opengl {
class COpenGLScene;
}

namespace roadslam::viewer {

enum class ColorBy { Height, Intensity, Ring, Time };
enum class CameraMode { Follow, TopDown, Orbit };
const char* toString(ColorBy c);
const char* toString(CameraMode c);
/// "height" / "intensity" / "ring" / "time"; throws std::invalid_argument naming the valid ones.
ColorBy parseColorBy(const std::string& s);
/// "follow" / "top" / "orbit"; throws std::invalid_argument naming the valid ones.
CameraMode parseCameraMode(const std::string& s);

struct SceneOptions {
  ColorBy color_by = ColorBy::Height;
  CameraMode camera = CameraMode::Follow;
  bool show_sweep = true, show_map = true, show_trajectory = true, show_ground_truth = true, show_loops = true,
       show_boundaries = true, show_keyframes = true, show_objects = true;
  float sweep_point_px = 2.0f;     ///< point size of the current sweep [pixels]
  float map_point_px = 1.0f;       ///< point size of the map [pixels]
  float line_px = 3.0f;            ///< trajectory line width [pixels]
  double height_min_m = -2.5;      ///< colour scale of "height": z relative to the lidar [m]
  double height_max_m = 3.0;
  double intensity_max = 100;      ///< colour scale of "intensity" [0..255 sensor units]
  double follow_distance_m = 35;   ///< follow camera: distance to the car [m]
  double follow_elevation_deg = 30;
  double top_height_m = 90;        ///< top-down camera: distance above the car [m]
  double orbit_azimuth_deg = -60;  ///< orbit camera, set by the user's mouse / keys
  double orbit_elevation_deg = 35;
  double orbit_distance_m = 60;
  bool hud = true;                 ///< a text line with time, observation and colour mode
  bool plots = true;               ///< the strip of per-frame odometry figures under the view (plots.h)
};

/// Colours of the overlays (RGB 0-255), fixed so tests and readers can find them in a picture.
struct SceneColors {
  static constexpr unsigned char trajectory[3] = {255, 0, 255};   // magenta: not in the jet colour map
  static constexpr unsigned char ground_truth[3] = {255, 255, 255};
  static constexpr unsigned char loop[3] = {255, 140, 0};
  static constexpr unsigned char left[3] = {255, 60, 60};
  static constexpr unsigned char right[3] = {60, 160, 255};
  static constexpr unsigned char free_space[3] = {60, 200, 60};
  static constexpr unsigned char map[3] = {120, 120, 130};
  static constexpr unsigned char grid_occupied[3] = {255, 200, 0};  // amber
  static constexpr unsigned char grid_free[3] = {45, 60, 75};
  static constexpr unsigned char background[3] = {25, 25, 30};
  static constexpr unsigned char object_moving[3] = {255, 50, 150};     // pink: a moving track's box, id, arrow
  static constexpr unsigned char object_static[3] = {0, 230, 160};      // teal: a static track
  static constexpr unsigned char object_untracked[3] = {200, 200, 120}; // khaki: an object no confirmed track took
};

/// What is shown at one instant.
struct SceneState {
  double t_s = 0;                          ///< replay time [s]
  std::optional<std::size_t> observation;  ///< index of the observation shown (for the HUD)
  const SweepPoints* sweep = nullptr;      ///< its points, when it has any
};

/// Where the camera looks from: the point it orbits and its spherical position around it (MRPT's
/// CCamera model: azimuth from +x, elevation above the xy plane, distance to the target).
struct CameraView {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< map frame [m]
  double azimuth_deg = 0, elevation_deg = 0, distance_m = 10;
};

/// Fills \p scene (cleared first) for \p state; returns the camera the options ask for (the
/// renderer and the window apply it: neither reads the viewport's own camera).
CameraView buildScene(const ViewerModel& model, const SceneState& state, const SceneOptions& options,
                mrpt::opengl::COpenGLScene& scene);

/// The lidar pose the sweep at \p t_s is drawn at: the nearest frame result, else the last one
/// before, else identity (no results: the lidar frame).
Eigen::Isometry3d poseAt(const ViewerModel& model, double t_s);

}  // namespace roadslam::viewer
