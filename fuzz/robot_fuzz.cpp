// Fuzz target: the robot readers (URDF, MJCF, SDF), the Collada reader, the audit and the
// rewriting of fixed inertials. Each input is read as a robot file and as a Collada mesh, in
// memory (mesh URIs are resolved in the scratch folder, never opened).
// Promise: a malformed file is an InputError naming the file and the line — never a crash, a
// hang, another exception or an allocation far beyond the input's size — an accepted robot is
// audited to finite numbers, and the file with its fixes written back reads again.

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "chasles/analysis/audit.h"
#include "chasles/error.h"
#include "chasles/files/collada_reader.h"
#include "chasles/files/robot_reader.h"
#include "chasles/files/robot_writer.h"
#include "chasles/report/audit_json.h"
#include "chasles/report/json_report.h"
#include "fuzz_support.h"

namespace {

void AuditAndRewrite(const chasles::RobotModel& model) {
  const chasles::RobotAudit audit = chasles::AuditRobot(model, chasles::AuditOptions{});
  try {
    chasles::CheckFiniteJson(chasles::AuditJson({audit}), "the audit");
  } catch (const chasles::InputError& e) {
    chasles::fuzz::Fail("the audit of an accepted robot is not finite", e.what());
  }
  std::vector<chasles::InertialRewrite> fixes;
  for (std::size_t i = 0; i < audit.links.size(); ++i) {
    const chasles::Finding* f = chasles::FixToApply(audit.links[i]);
    if (!f) continue;
    fixes.push_back({i, f->fix->mass(), f->fix->p_BoBcm_B(), f->fix->I_BBcm_B().matrix(), "fix"});
  }
  std::string text;
  try {
    text = chasles::RewriteInertials(model, fixes);
  } catch (const chasles::InputError&) {
    return;  // a value with no text to rewrite (an SDF default) is said so
  }
  try {
    chasles::ReadRobotBytes(text, model.file);
  } catch (const chasles::InputError& e) {
    chasles::fuzz::Fail("the fixed file does not read again", e.what());
  }
}

/// The reader's error names the file and a line ("NAME:LINE: ..."), but for a file too large to
/// read at all.
void CheckFileAndLine(const std::string& name, const std::string& what) {
  if (what.find("larger than the limit") != std::string::npos) return;
  std::size_t i = name.size() + 1;
  const bool named =
      what.compare(0, name.size(), name) == 0 && what.size() > i && what[i - 1] == ':';
  while (named && i < what.size() && what[i] >= '0' && what[i] <= '9') ++i;
  if (!named || i == name.size() + 1 || i >= what.size() || what[i] != ':') {
    chasles::fuzz::Fail("a robot file's error without its file and line", what);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string name = (chasles::fuzz::ScratchDir() / "urdf" / "fuzz.urdf").string();
  try {
    AuditAndRewrite(chasles::ReadRobotBytes(bytes, name));
  } catch (const chasles::InputError& e) {
    CheckFileAndLine(name, e.what());
  } catch (const std::exception& e) {
    chasles::fuzz::Fail(e.what(), "robot");
  }
  try {
    const chasles::TriangleSoup soup = chasles::ReadColladaBytes(bytes, "fuzz.dae");
    for (const double c : soup.xyz) {
      if (!std::isfinite(c)) chasles::fuzz::Fail("a non-finite Collada coordinate", "dae");
    }
    for (const std::uint32_t i : soup.indices) {
      if (i >= soup.vertex_count()) chasles::fuzz::Fail("a Collada index out of range", "dae");
    }
  } catch (const chasles::InputError&) {
  } catch (const std::exception& e) {
    chasles::fuzz::Fail(e.what(), "dae");
  }
  return 0;
}
