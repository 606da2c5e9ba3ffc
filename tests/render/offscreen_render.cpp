#include "tests/render/offscreen_render.h"

#include <GLFW/glfw3.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>

// LeakSanitizer cannot attribute what the GL driver allocates: Mesa unloads it before exit, so its frames
// are an "unknown module" no suppression can name. Leak checking is off for this program only (LSan asks
// this function at exit); every other sanitizer check stays on.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OPENPLX_RENDER_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(OPENPLX_RENDER_UNDER_ASAN)
extern "C" int __lsan_is_turned_off() {
  return 1;
}
#endif

namespace openplx::testing {
namespace {

std::string glfw_error;

void keep_glfw_error(int, const char* description) {
  glfw_error = description ? description : "unknown GLFW error";
}

// Starts `Xvfb -displayfd`, which writes the display number it took to the pipe once it accepts clients.
// Returns its pid and sets DISPLAY, or -1 with the reason.
int start_xvfb(std::string& why_not, bool& not_installed) {
  int fds[2];
  if (pipe(fds) != 0) {
    why_not = "no pipe for Xvfb";
    return -1;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    const std::string fd = std::to_string(fds[1]);
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "640x480x24", "-nolisten", "tcp",
           static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  if (pid < 0) {
    close(fds[0]);
    why_not = "could not fork for Xvfb";
    return -1;
  }
  std::string number;
  pollfd wait_for{fds[0], POLLIN, 0};
  char c = 0;
  // Xvfb answers within a second or two; 20 s allows for a machine busy with a parallel build.
  while (poll(&wait_for, 1, 20000) > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
  close(fds[0]);
  if (number.empty()) {
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    not_installed = WIFEXITED(status) && WEXITSTATUS(status) == 127;
    why_not =
        not_installed ? "no X display and no Xvfb to start one (apt-get install xvfb)" : "Xvfb did not start";
    return -1;
  }
  setenv("DISPLAY", (":" + number).c_str(), 1);
  return pid;
}

void stop(int pid) {
  if (pid <= 0) return;
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
}

}  // namespace

std::vector<double> Rendered::median_colour(int geom_id, const std::vector<bool>& mask) const {
  std::vector<std::vector<unsigned char>> channels(3);
  for (size_t p = 0; p < geom.size(); ++p) {
    if (geom[p] != geom_id || (!mask.empty() && !mask[p])) continue;
    for (int c = 0; c < 3; ++c) channels[c].push_back(rgb[3 * p + c]);
  }
  std::vector<double> median;
  for (std::vector<unsigned char>& values : channels) {
    if (values.empty()) return {};
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    median.push_back(values[values.size() / 2]);
  }
  return median;
}

void Rendered::write_ppm(const std::string& path) const {
  std::ofstream out(path, std::ios::binary);
  out << "P6 " << width << " " << height << " 255\n";
  for (int row = height - 1; row >= 0; --row)
    out.write(reinterpret_cast<const char*>(&rgb[3 * size_t(row) * width]), 3 * width);
}

// An invisible window on the current DISPLAY, its context current; false with GLFW's error.
bool OffscreenRenderer::open_window(std::string& why_not) {
  glfwSetErrorCallback(keep_glfw_error);
  if (!glfwInit()) {
    why_not = "GLFW could not start: " + glfw_error;
    return false;
  }
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width_, height_, "offscreen", nullptr, nullptr);
  if (!window) {
    why_not = "no OpenGL window: " + glfw_error;
    glfwTerminate();
    return false;
  }
  glfwMakeContextCurrent(window);
  window_ = window;
  return true;
}

std::unique_ptr<OffscreenRenderer> OffscreenRenderer::open(int width, int height, std::string& why_not,
                                                           bool& no_server) {
  std::unique_ptr<OffscreenRenderer> r(new OffscreenRenderer(width, height));
  no_server = false;
  // The display the test was given, if it works; else (none, or one that is gone) an Xvfb of our own.
  const char* display = std::getenv("DISPLAY");
  if (display && *display && r->open_window(why_not)) return r;
  r->xvfb_pid_ = start_xvfb(why_not, no_server);
  if (r->xvfb_pid_ < 0) return nullptr;
  if (r->open_window(why_not)) return r;
  r->stop_own_display();
  return nullptr;
}

OffscreenRenderer::~OffscreenRenderer() {
  if (window_) {
    glfwDestroyWindow(static_cast<GLFWwindow*>(window_));
    glfwTerminate();
  }
  stop_own_display();
}

void OffscreenRenderer::stop_own_display() {
  if (xvfb_pid_ <= 0) return;
  stop(xvfb_pid_);
  xvfb_pid_ = -1;
  unsetenv("DISPLAY");  // it named the server just stopped
}

Rendered OffscreenRenderer::render(mjModel* m, mjData* d, const mjvCamera& camera) {
  m->vis.global.offwidth = width_;
  m->vis.global.offheight = height_;
  mjvScene scene;
  mjvOption option;
  mjrContext context;
  mjv_defaultScene(&scene);
  mjv_defaultOption(&option);
  mjr_defaultContext(&context);
  mjv_makeScene(m, &scene, 2000);
  mjr_makeContext(m, &context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &context);
  mjvCamera cam = camera;
  mjv_updateScene(m, d, &option, nullptr, &cam, mjCAT_ALL, &scene);
  const mjrRect viewport{0, 0, width_, height_};
  Rendered out;
  out.width = width_;
  out.height = height_;
  out.rgb.resize(3 * size_t(width_) * height_);
  mjr_render(viewport, &scene, &context);
  mjr_readPixels(out.rgb.data(), nullptr, viewport, &context);
  // Segmentation: each scene geom drawn flat in the colour of its index + 1.
  scene.flags[mjRND_SEGMENT] = 1;
  scene.flags[mjRND_IDCOLOR] = 1;
  std::vector<unsigned char> ids(out.rgb.size());
  mjr_render(viewport, &scene, &context);
  mjr_readPixels(ids.data(), nullptr, viewport, &context);
  out.geom.assign(size_t(width_) * height_, -1);
  for (size_t p = 0; p < out.geom.size(); ++p) {
    const int segment = ids[3 * p] + 256 * ids[3 * p + 1] + 65536 * ids[3 * p + 2] - 1;
    if (segment < 0 || segment >= scene.ngeom) continue;
    const mjvGeom& g = scene.geoms[segment];
    if (g.objtype == mjOBJ_GEOM) out.geom[p] = g.objid;
  }
  mjr_freeContext(&context);
  mjv_freeScene(&scene);
  return out;
}

}  // namespace openplx::testing
