// Drives samples/cart_pole and samples/vehicle_circle, as openplx2mjcf emitted them into DIR, through their
// signal manifests alone (signal_client.mjs, no C++ runtime) in current MuJoCo (mujoco-js), and checks what
// they do physically; then checks that the client says which signals of samples/drivetrain_machine it cannot
// drive exactly (its engine is a law the runtime computes). Prints `PASS what` / `FAIL what` lines and exits
// 1 on any failure. Usage: node drive_samples.mjs DIR (DIR holds cart_pole.xml, vehicle_circle.xml,
// drivetrain_machine.xml and their .signals.json).
import fs from 'node:fs';
import path from 'node:path';
import loadMujoco from 'mujoco-js';
import {SignalClient, ClientError} from './signal_client.mjs';

const dir = path.resolve(process.argv[2]);
const mujoco = await loadMujoco({print: () => {}, printErr: () => {}});
let failures = 0;

function check(ok, what) {
  console.log(`${ok ? 'PASS' : 'FAIL'} ${what}`);
  if (!ok) ++failures;
}

// The module has no host file system: the MJCF goes into its in-memory one.
function load(name) {
  const file = path.join(dir, name + '.xml');
  mujoco.FS.writeFile('/' + name + '.xml', fs.readFileSync(file));
  const model = mujoco.MjModel.loadFromXML('/' + name + '.xml');
  const data = new mujoco.MjData(model);
  const manifest = JSON.parse(fs.readFileSync(path.join(dir, name + '.signals.json'), 'utf8'));
  const client = new SignalClient(mujoco, model, data, manifest);
  mujoco.mj_forward(model, data);
  return {model, data, client, dispose: () => { data.delete(); model.delete(); }};
}

function run({model, data, client}, seconds, each = () => {}) {
  const steps = Math.round(seconds / model.opt.timestep);
  for (let k = 0; k < steps; ++k) {
    each(k * model.opt.timestep);
    mujoco.mj_step(model, data);
    client.afterStep();
  }
}

// cart_pole: a force on the cart by its `push` input moves the cart that way, about as F t^2 / (2 (M + m))
// while the pole is near upright, and the pole lags behind (it tilts against the push).
function cartPole(force) {
  const sim = load('cart_pole');
  const {client, model} = sim;
  const push = client.input('push');
  const position = client.output('cart_position'), angle = client.output('pole_angle');
  const applied = client.output('drive.force_output');
  const cart = client.output('cart.position_output'), pole = client.output('pole.position_output');
  const total = model.body_mass[1] + model.body_mass[2];
  const t = 0.3;
  run(sim, t, () => push.set(force));
  const x = position.read(), expected = force * t * t / (2 * total);
  check(push.exact && position.exact, `cart_pole: push and cart_position are exact without the runtime`);
  if (force !== 0) check(Math.abs(x - expected) < 0.25 * Math.abs(expected),
        `cart_pole: push ${force} N for ${t} s moved the cart ${x.toFixed(4)} m (F t^2 / 2 (M + m) = ` +
        `${expected.toFixed(4)} m)`);
  check(Math.abs(applied.read() - force) < 1e-9, `cart_pole: drive.force_output reads the push (${applied.read()} N)`);
  const lag = pole.read()[0] - cart.read()[0];
  if (force !== 0) check(Math.sign(lag) === -Math.sign(force), `cart_pole: the pole lags behind the cart (${lag.toFixed(4)} m)`);
  // The manifest's sensor carries the same value as the quantity's reading.
  // The manifest's sensor carries the same value as the quantity's reading (sensors are computed in the
  // step's first stage, so at the state mj_forward computes them for).
  mujoco.mj_forward(model, sim.data);
  const sensor = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR.value, position.binding.sensor);
  check(sim.data.sensordata[model.sensor_adr[sensor]] === x, 'cart_pole: cart_position equals its MuJoCo sensor');
  const result = {x, angle: angle.read()};
  sim.dispose();
  return result;
}

// vehicle_circle: `speed` (a broadcast to both rear motors' target, rad/s) drives it forward (+x, where its
// front wheels are), `steering` turns it left for positive angles, right for negative ones, on a circle about
// as wide as Ackermann geometry gives.
function vehicle(steering) {
  const sim = load('vehicle_circle');
  const {client} = sim;
  const position = client.output('position');
  const speed = client.input('speed'), steer = client.input('steering');
  // The rear motors are the runtime's rows; without it their stand-in servos lag under load, and the
  // manifest says so.
  check(!speed.exact && steer.exact,
        `vehicle_circle: the client says speed needs the runtime; steering is exact without it`);
  run(sim, 1.0);  // settle on the suspensions
  const start = position.read();
  speed.set(8);
  steer.set(steering);
  const track = [];
  run(sim, 6.0, (t) => { if (Math.abs(t % 0.5) < 1e-9) track.push(position.read()); });
  const end = position.read();
  check(Math.abs(client.output('steering_angle').read() - steering) < 1e-3,
        `vehicle_circle: steering_angle follows steering ${steering} (${client.output('steering_angle').read().toFixed(5)})`);
  sim.dispose();
  return {start, end, track};
}

// Signed curvature of a path through three points (> 0: turning left, counterclockwise seen from above).
function curvature(a, b, c) {
  const ab = [b[0] - a[0], b[1] - a[1]], bc = [c[0] - b[0], c[1] - b[1]], ac = [c[0] - a[0], c[1] - a[1]];
  const turn = ab[0] * bc[1] - ab[1] * bc[0];
  return 2 * turn / (Math.hypot(...ab) * Math.hypot(...bc) * Math.hypot(...ac));
}

try {
  // Within the drive's effort range (+-10 N); unpushed, the pole falls from its initial tilt.
  const forward = cartPole(8), backward = cartPole(-8), unpushed = cartPole(0);
  check(forward.x > 0 && backward.x < 0 && unpushed.x !== forward.x, 'cart_pole: the cart moves the way the push says');
  const ahead = forward.angle - unpushed.angle, behind = backward.angle - unpushed.angle;
  check(Math.sign(ahead) === -Math.sign(behind) && ahead !== 0,
        `cart_pole: opposite pushes tilt the pole opposite ways from its unpushed fall (${ahead.toFixed(5)}, ` +
        `${behind.toFixed(5)} rad)`);

  const straight = vehicle(0);
  const dx = straight.end[0] - straight.start[0], dy = straight.end[1] - straight.start[1];
  check(dx > 10 && Math.abs(dy) < 0.05 * dx, `vehicle_circle: speed 8 rad/s drives it forward ${dx.toFixed(3)} m in 6 s ` +
        `(sideways ${dy.toFixed(4)} m)`);
  const wheelbase = 2.5, track = 1.6;
  for (const steering of [0.3, -0.3]) {
    const turn = vehicle(steering);
    const [a, b, c] = [turn.track[2], turn.track[6], turn.track[10]];
    const k = curvature(a, b, c);
    // `steering` is the left front wheel's angle: inner in a left turn, outer in a right one. The rear axle's
    // middle turns on wheelbase / tan|steering| plus or minus half the track.
    const radius = wheelbase / Math.tan(Math.abs(steering)) + Math.sign(steering) * track / 2;
    check(Math.sign(k) === Math.sign(steering), `vehicle_circle: steering ${steering} turns it ${k > 0 ? 'left' : 'right'}`);
    check(Math.abs(1 / Math.abs(k) - radius) < 0.1 * radius,
          `vehicle_circle: steering ${steering}: radius ${(1 / Math.abs(k)).toFixed(3)} m (Ackermann ${radius.toFixed(3)} m)`);
  }

  // What the client cannot drive exactly: the engine's throttle (its torque curve is a runtime law).
  const machine = load('drivetrain_machine');
  const throttle = machine.client.input('throttle');
  check(!throttle.exact, 'drivetrain_machine: the client says the throttle needs the runtime');
  check(machine.client.warnings.some((w) => w.startsWith('engine `') && w.includes('static stand-in')),
        'drivetrain_machine: the client says the engine law runs as its static stand-in');
  check(machine.client.warnings.some((w) => w.includes('input `throttle` needs the runtime each step')),
        'drivetrain_machine: the throttle warning names the runtime');
  let refused = '';
  try {
    machine.client.input('chassis.linear_velocity_world_input');
  } catch (e) {
    refused = e instanceof ClientError ? e.message : String(e);
  }
  check(refused === '' || refused.includes('not mapped'), `drivetrain_machine: an unmapped input is refused by name`);
  machine.dispose();
} catch (e) {
  check(false, `exception: ${e && e.stack ? e.stack : e}`);
}
console.log(failures ? `${failures} checks failed` : 'all checks passed');
process.exit(failures ? 1 : 0);
