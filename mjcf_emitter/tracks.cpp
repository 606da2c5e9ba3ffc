// Lowering pass, tracks (Vehicles.TrackSystem): link_count rigid links hinged into a closed chain around the
// track wheels. The belt line runs height / 2 outside each wheel: straight tangents between consecutive
// wheels (counter-clockwise about the axle, the wheels taken as the corners of a convex hull) and arcs
// around them; its length is split into equal pitches, one link per pitch, each a box from one hinge point
// to the next. The chain is MuJoCo bodies nested in chains of at most kChainLinks (MuJoCo's reader stops
// near 100 nested elements), each chain's root free, closed to the next by two `connect`s on the hinge
// axis. The wheels drive and carry the links through contact (the sprocket's friction; no teeth).
#include <Eigen/Geometry>
#include <cmath>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {
namespace {

constexpr int kChainLinks = 40;

// Track links touch wheels and ground in many places at once: room for 4 contacts (16 constraint rows) per
// link beyond MuJoCo 2.2.2's defaults (100 contacts, 500 rows). A driven 200-link track used at most 1.7
// contacts and 7 rows per link. MuJoCo 2.2.2 allocates its stack dense in the rows (about 40 rows^2 bytes:
// 1.3 GB at 300 links, 0.4 GB resident; 200 links of the old 64 rows per link no longer loaded), so the links
// of all tracks together are bounded by kMaxLinks, which snap/resolve_system.cpp also holds each track's
// link_count to.
constexpr int kRowsPerLink = 16;
constexpr int kContactsPerLink = 4;
constexpr int kMaxLinks = 300;

struct Circle {
  Eigen::Vector2d centre;
  double radius;
};

// A point of the closed belt line at arc length s (0 <= s < length), and the line's total length.
class BeltLine {
 public:
  explicit BeltLine(const std::vector<Circle>& circles) : circles_(circles) {
    const size_t n = circles.size();
    for (size_t i = 0; i < n; ++i) {
      const Circle &a = circles[i], &b = circles[(i + 1) % n];
      const Eigen::Vector2d d = b.centre - a.centre;
      const double l = d.norm(), c = (a.radius - b.radius) / l;
      const Eigen::Vector2d u = d / l, right(u.y(), -u.x());
      normals_.push_back(c * u +
                         std::sqrt(std::max(0.0, 1 - c * c)) * right);  // outer tangent, outside right
    }
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d from = circles[i].centre + circles[i].radius * normals_[i];
      const Eigen::Vector2d to = circles[(i + 1) % n].centre + circles[(i + 1) % n].radius * normals_[i];
      segments_.push_back({from, to, (to - from).norm()});
      // The arc on the next circle, counter-clockwise from this tangent's normal to the next one's.
      const Eigen::Vector2d in = normals_[i], out = normals_[(i + 1) % n];
      double sweep = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out));
      if (sweep < 0) sweep += 2 * M_PI;
      arcs_.push_back({std::atan2(in.y(), in.x()), sweep});
      length_ += segments_.back().length + sweep * circles[(i + 1) % n].radius;
    }
  }
  double length() const { return length_; }
  Eigen::Vector2d at(double s) const {
    for (size_t i = 0; i < segments_.size(); ++i) {
      const Segment& seg = segments_[i];
      if (s <= seg.length) return seg.from + (seg.to - seg.from) * (s / seg.length);
      s -= seg.length;
      const Circle& c = circles_[(i + 1) % circles_.size()];
      const double arc = arcs_[i].second * c.radius;
      if (s <= arc) {
        const double angle = arcs_[i].first + s / c.radius;
        return c.centre + c.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      }
      s -= arc;
    }
    return segments_.front().from;
  }

 private:
  struct Segment {
    Eigen::Vector2d from, to;
    double length;
  };
  std::vector<Circle> circles_;
  std::vector<Eigen::Vector2d> normals_;
  std::vector<Segment> segments_;
  std::vector<std::pair<double, double>> arcs_;  // start angle, counter-clockwise sweep
  double length_ = 0;
};

}  // namespace

void Lowering::emit_tracks(Element& root) {
  int64_t links = 0;  // of the tracks emitted
  for (const sn::TrackSystem& t : system_.tracks) {
    const bool wheels_known = std::all_of(t.wheels.begin(), t.wheels.end(), [](const auto& w) {
      return w.connector >= 0 && w.radius > 0 && std::isfinite(w.radius);
    });
    if (t.wheels.size() < 2 || !wheels_known || t.link_count < 3 || t.link_count > kMaxLinks ||
        !(t.link_width > 0) || !(t.link_height > 0) || !std::isfinite(t.link_width + t.link_height)) {
      warn(t.where, "track system `" + t.path +
                        "` needs two or more wheels with radii and center connectors and 3 to " +
                        std::to_string(kMaxLinks) +
                        " links of positive width and height; its track was left out");
      continue;
    }
    if (links + t.link_count > kMaxLinks) {
      sink_.report(fe::DiagCode::MjcfTooLarge, t.where,
                   "track system `" + t.path + "` brings the model's track links to " +
                       std::to_string(links + t.link_count) + "; MuJoCo 2.2.2 cannot allocate the contact " +
                       "room of more than " + std::to_string(kMaxLinks) + " links in one model (fewer, " +
                       "longer links would do)");
      continue;
    }
    links += t.link_count;
    // The belt's plane: across the first wheel's axle, through the wheels' centres.
    const sn::Transform first = snap_.connector_world[t.wheels.front().connector];
    const Eigen::Vector3d axle = first.rotation * Eigen::Vector3d::UnitZ();
    Eigen::Vector3d along = snap_.connector_world[t.wheels.back().connector].position - first.position;
    along -= along.dot(axle) * axle;
    if (along.norm() < 1e-9) along = first.rotation * Eigen::Vector3d::UnitX();
    along.normalize();
    const Eigen::Vector3d across = axle.cross(along);
    std::vector<Circle> circles;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const auto& w : t.wheels) {
      const Eigen::Vector3d p = snap_.connector_world[w.connector].position - first.position;
      circles.push_back({{p.dot(along), p.dot(across)}, w.radius + t.link_height / 2});
      centroid += circles.back().centre / static_cast<double>(t.wheels.size());
    }
    // Counter-clockwise about the axle: the hull's corners in angle order about the centroid.
    std::sort(circles.begin(), circles.end(), [&](const Circle& a, const Circle& b) {
      const Eigen::Vector2d da = a.centre - centroid, db = b.centre - centroid;
      return std::atan2(da.y(), da.x()) < std::atan2(db.y(), db.x());
    });
    // Consecutive wheels must be apart, neither inside the other, for the belt to have outer tangents.
    bool separate = true;
    for (size_t i = 0; i < circles.size(); ++i) {
      const Circle &a = circles[i], &b = circles[(i + 1) % circles.size()];
      separate = separate && (b.centre - a.centre).norm() > std::abs(a.radius - b.radius) + 1e-9;
    }
    if (!separate) {
      warn(t.where, "track system `" + t.path +
                        "` has wheels at one place or one inside another; its track was left out");
      continue;
    }
    const BeltLine line(circles);
    const int n = t.link_count;
    const double pitch = line.length() / n;
    auto world_point = [&](const Eigen::Vector2d& q) {
      return Eigen::Vector3d(first.position + q.x() * along + q.y() * across);
    };
    // Link k: from hinge point k to k + 1; its frame has x along that chord and z along the axle.
    std::vector<sn::Transform> frames(n);
    std::vector<double> chords(n);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d a = world_point(line.at(k * pitch)),
                            b = world_point(line.at(((k + 1) % n) * pitch));
      chords[k] = (b - a).norm();
      Eigen::Matrix3d r;
      r.col(0) = (b - a).normalized();
      r.col(2) = axle;
      r.col(1) = axle.cross(r.col(0));
      frames[k] = {a, Eigen::Quaterniond(r)};
    }
    const double mass = t.link_mass > 0 ? t.link_mass : t.link_density * pitch * t.link_width * t.link_height;
    Element* equality = root.child("equality");
    Element* contact = root.child("contact");
    std::vector<std::string> names(n);
    Element* parent = nullptr;
    for (int k = 0; k < n; ++k) {
      names[k] = name(t.path) + ".link" + std::to_string(k);
      const bool chain_root = k % kChainLinks == 0;
      Element& body = chain_root ? world_->add("body") : parent->add("body");
      const sn::Transform pose =
          chain_root ? frames[k] : natives::affine_compose(natives::affine_inverse(frames[k - 1]), frames[k]);
      body.set("name", names[k]).set("pos", pose.position).set_quat("quat", pose.rotation);
      if (chain_root) {
        body.add("freejoint").set("name", names[k]);
      } else {
        body.add("joint").set("name", names[k]).set("type", "hinge").set("pos", "0 0 0").set("axis", "0 0 1");
      }
      body.add("geom")
          .set("name", names[k])
          .set("type", "box")
          .set("size", Eigen::Vector3d(chords[k] / 2, t.link_height / 2, t.link_width / 2))
          .set("pos", Eigen::Vector3d(chords[k] / 2, 0, 0))
          .set("mass", mass);
      if (t.chassis >= 0 && body_element_.count(t.chassis))
        contact->add("exclude").set("body1", name(system_.nodes[t.chassis].path)).set("body2", names[k]);
      parent = &body;
    }
    // Each chain's last link holds the next chain's root (the last chain the first): two points on the
    // hinge axis make a hinge.
    for (int k = 0; k < n; ++k) {
      const int next = (k + 1) % n;
      if (next % kChainLinks != 0) continue;
      for (const double side : {-1.0, 1.0}) {
        equality->add("connect")
            .set("name", name(t.path) + ".closure" + std::to_string(next) + (side < 0 ? ".a" : ".b"))
            .set("body1", names[k])
            .set("body2", names[next])
            .set("anchor", Eigen::Vector3d(chords[k], 0, side * t.link_width / 2));
      }
      contact->add("exclude").set("body1", names[k]).set("body2", names[next]);
    }
    warn(t.where,
         "track system `" + t.path + "` is " + std::to_string(n) + " rigid links of " + number(pitch) +
             " m on hinges: its flexibility, damping, bending range and tension initialisation are not "
             "mapped, and its wheels drive it by friction");
  }
  const int n = static_cast<int>(links);  // at most kMaxLinks
  size_contact_buffers(root, kContactsPerLink * n, kRowsPerLink * n);
}

}  // namespace openplx::mjcf
