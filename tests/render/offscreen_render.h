// MuJoCo 2.2.2's own renderer (mjv_updateScene, mjr_render into its offscreen buffer, mjr_readPixels) in an
// OpenGL context of an invisible GLFW window. Without a display, an X server of its own is started (Xvfb,
// which picks a free display number itself: tests running at once never meet). Every pixel is also read
// back as the model geom it shows (MuJoCo's segmentation colours), so a test picks the floor by name.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

namespace openplx::testing {

struct Rendered {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // bottom row first, as OpenGL reads it
  std::vector<int> geom;           // the model geom id each pixel shows, -1 for none (sky, decorations)
  // Each channel's median over the pixels that show `geom_id` and are also in `mask` (when not empty).
  std::vector<double> median_colour(int geom_id, const std::vector<bool>& mask = {}) const;
  // A binary PPM, for looking at (tools like ImageMagick's convert turn it into a PNG).
  void write_ppm(const std::string& path) const;
};

class OffscreenRenderer {
 public:
  // Empty when a context could not be made, with why in `why_not`; `no_server` then says whether that was
  // for want of any X server (no DISPLAY and no Xvfb installed), the one reason a test may skip.
  static std::unique_ptr<OffscreenRenderer> open(int width, int height, std::string& why_not,
                                                 bool& no_server);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // The model at `d`'s state seen from `camera`, with MuJoCo's default visual options.
  Rendered render(mjModel* m, mjData* d, const mjvCamera& camera);

 private:
  OffscreenRenderer(int width, int height) : width_(width), height_(height) {}
  int width_, height_;
  bool open_window(std::string& why_not);
  void stop_own_display();
  int xvfb_pid_ = -1;
  void* window_ = nullptr;
};

}  // namespace openplx::testing
