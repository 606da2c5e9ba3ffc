#!/bin/sh
# The installed CMake package used by an outside project (samples/controller): find_package(openplx2mjcf),
# the runtime library, openplx2mjcf_add_model converting cart_pole at build time, and two_carts balancing two
# placed copies in one scene (exits non-zero when a pole falls or a cart runs off). A build with nothing
# changed converts nothing; touching the model, or a bundle file the conversion read (the converter's
# --depfile), converts again. A program built with Eigen hidden from CMake uses the bridge through std::array.
#   installed_package_test.sh BUILD_DIR SOURCE_DIR
set -e
build=$1
source=$2
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
cmake --install "$build" --prefix "$t/prefix" >/dev/null
mkdir "$t/models"
cp "$source/samples/cart_pole.openplx" "$t/models/"
# Built with make itself: the project is the test's own, and make's output is what is checked.
cmake -S "$source/samples/controller" -B "$t/build" -G "Unix Makefiles" -DCMAKE_PREFIX_PATH="$t/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DOPENPLX_SAMPLE_MODELS="$t/models" >/dev/null
make -C "$t/build" -j2 >"$t/first.log"
grep -q "Converting .*cart_pole.openplx to left_cart_pole.xml" "$t/first.log"
"$t/build/arm_controller" "$source/samples/two_joint_arm.openplx"
"$t/build/machine_driver" "$source/samples/drivetrain_machine.openplx"
(cd "$t/build" && ./two_carts two_carts_scene.xml left_cart_pole.signals.json right_cart_pole.signals.json)
# two_carts links openplx2mjcf::bridge: no library of the converter (front end, SNAP, emitter, runtime loader).
link=$(cat "$t/build/CMakeFiles/two_carts.dir/link.txt")
echo "two_carts link line: $link"
if echo "$link" | grep -Eq 'libopenplx_(frontend|snap|mjcf|runtime|cli)\.a'; then
  echo "error: the bridge-only controller links a converter library" >&2
  exit 1
fi
echo "$link" | grep -q 'libopenplx_bridge\.a'

# A program that uses the bridge without Eigen (Eigen3 hidden from CMake): vector signals as std::array.
mkdir "$t/no_eigen"
cat >"$t/no_eigen/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.16)
project(no_eigen CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(openplx2mjcf REQUIRED)
add_executable(no_eigen main.cpp)
target_link_libraries(no_eigen openplx2mjcf::bridge)
CMAKE
cat >"$t/no_eigen/main.cpp" <<'CPP'
#include <openplx/runtime/signal_bridge.h>

#include <cstdio>

#if OPENPLX_RUNTIME_HAS_EIGEN
#error "Eigen was hidden from this project"
#endif

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof(error));
  if (!m) return 1;
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  {
    auto bridge = openplx::runtime::SignalBridge::attach(argv[2], m, d);
    bridge.input("push").set(5.0);
    const openplx::runtime::Output cart = bridge.output("cart.position_output");
    const std::array<double, 3> start = cart.vec3_values();
    for (int k = 0; k < 500; ++k) {
      bridge.before_step();
      mj_step(m, d);
      bridge.after_step();
    }
    const std::array<double, 3> end = cart.vec3_values();
    std::printf("without Eigen: the cart moved %.3f m along x\n", end[0] - start[0]);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
CPP
cmake -S "$t/no_eigen" -B "$t/no_eigen/build" -DCMAKE_PREFIX_PATH="$t/prefix" -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
make -C "$t/no_eigen/build" >/dev/null
"$t/no_eigen/build/no_eigen" "$t/build/left_cart_pole.xml" "$t/build/left_cart_pole.signals.json"

# A later mtime than anything built, whatever the file system's timestamp resolution.
later() { touch -d "@$(($(date +%s) + $1))" "$2"; }
rebuilt() { make -C "$t/build" -j2 >"$t/again.log" && grep -c "Converting" "$t/again.log" || true; }
echo "nothing changed: $(rebuilt) conversions"
later 5 "$t/models/cart_pole.openplx"
echo "model touched: $(rebuilt) conversions"
bundle_file="$t/prefix/share/openplx2mjcf/bundles/Physics3D/Bodies/RigidBody.openplx"
grep -q "$bundle_file" "$t/build/left_cart_pole.xml.d"
later 10 "$bundle_file"
echo "bundle file touched: $(rebuilt) conversions"
