#include "mjcf_emitter/soft_constraints.h"

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace openplx::mjcf {

namespace fs = std::filesystem;

SoftEqualityResult apply_soft_equalities(Element& document, const std::vector<PendingSoftEquality>& pending,
                                         const std::string& dir, double timestep) {
  SoftEqualityResult result;
  if (pending.empty()) return result;
  const fs::path folder = dir.empty() ? fs::temp_directory_path() : fs::path(dir);
  // The pid keeps processes apart, the counter threads and calls of one process.
  static std::atomic<unsigned> counter{0};
  const fs::path file = folder / (".openplx2mjcf-soft-" + std::to_string(::getpid()) + "-" +
                                  std::to_string(counter++) + ".xml");
  std::ofstream(file) << document.to_string();
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  std::error_code ec;
  fs::remove(file, ec);
  if (!m) {
    result.error = error;
    return result;
  }
  const double d = kSoftImpedance;
  for (const PendingSoftEquality& p : pending) {
    double dA = 0;
    for (const std::string& body : {p.body1, p.body2}) {
      const int id = body == "world" ? 0 : mj_name2id(m, mjOBJ_BODY, body.c_str());
      if (id > 0) dA += m->body_invweight0[2 * id];  // translational entry
    }
    const MateCompliance& c = p.compliance;
    const double ks = c.k_trans * (1 - d) * dA, bs = c.b_trans * (1 - d) * dA;
    p.equality->set("solref", number(-ks) + " " + number(-bs))
        .set("solimp", number(d) + " " + number(d) + " 0.001 0.5 2");
    if (p.weld && c.k_trans > 0) p.equality->set("torquescale", 4 * c.k_rot / c.k_trans);
    if (timestep * std::sqrt(ks) > 1 || timestep * bs > 1)
      result.unstable.push_back(*p.equality->get("name"));
  }
  mj_deleteModel(m);
  return result;
}

}  // namespace openplx::mjcf
