#!/usr/bin/env bash
# Installs what is missing, builds, and runs a sample model through openplx2mjcf.
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
# Only what runs below: the two tools and the modules they load (the URDF importer, the mesh reader), not the
# tests or benchmarks (./test.sh turns them on again in the same build/).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DOPENPLX_BUILD_TESTS=OFF -DOPENPLX_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target openplx2mjcf openplx-sim
sample=samples/pendulum.openplx
out=build/samples/pendulum.xml
mkdir -p build/samples
echo "== openplx2mjcf $sample --dump=snap   (world frames after SNAP assembly)"
build/tools/openplx2mjcf "$sample" --dump=snap
echo "== openplx2mjcf $sample -o $out --check   (MJCF, loaded back in MuJoCo and compared with SNAP)"
build/tools/openplx2mjcf "$sample" -o "$out" --check
cat "$out"
echo "== mujoco-testspeed $out 5000   (MuJoCo simulates it headless)"
mujoco-testspeed "$out" 5000 | grep -E "Simulation time|Steps per second|Degrees of freedom"
echo "== openplx-sim samples/cart_pole.openplx   (the runtime drives it by OpenPLX signal names)"
build/tools/openplx-sim samples/cart_pole.openplx --time 1 --set push=5 --at 0.5 push=-5 \
  --print cart_position --print cart_speed --print pole_angle
echo "== openplx-sim samples/drivetrain_machine.openplx   (engine, clutch, gearbox, differential: throttle, then brake)"
build/tools/openplx-sim samples/drivetrain_machine.openplx --time 6 --set throttle=0.5 --at 4 throttle=0 \
  --at 4 clutch=false --at 4 brake_left=1 --at 4 brake_right=1 --print position --print velocity --print engine_rpm
echo "== openplx-sim samples/vehicle_circle.openplx   (suspensions and Ackermann steering: a circle)"
build/tools/openplx-sim samples/vehicle_circle.openplx --time 10 --set steering=0.3 --set speed=8 \
  --print position --print steering_angle
echo "== openplx2mjcf tests/corpus/urdf/bullet3/r2d2.urdf --check   (a URDF robot through urdfdom, checked in MuJoCo)"
build/tools/openplx2mjcf tests/corpus/urdf/bullet3/r2d2.urdf -o build/samples/r2d2.xml --check
echo "== openplx-sim samples/urdf_pantilt.openplx   (a URDF robot extended in OpenPLX with motors and outputs)"
build/tools/openplx-sim samples/urdf_pantilt.openplx --time 1 --set pan_torque=50 --print pan_angle --print tilt_angle
