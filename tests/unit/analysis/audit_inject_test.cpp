// Seeded defects injected into the shared robots (../shared/robots; skipped without them): each
// class of defect at random links, written into the file's own text as a person would have
// written it. Each must be found with its code at its link and line, no error may appear on a
// link that was not touched, and the fix --fix would write must leave no error.

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "analysis/internal/audit_steps.h"
#include "chasles/analysis/audit.h"
#include "chasles/files/robot_reader.h"
#include "chasles/files/robot_writer.h"
#include "chasles/scene/robot_file.h"
#include "test_paths.h"
#include "test_support.h"

namespace chasles {
namespace {

/// A clean robot: its model, its audit, the error codes of each link.
struct Clean {
  RobotModel model;
  RobotAudit audit;
  std::vector<std::set<FindingCode>> errors;
};

std::set<FindingCode> Errors(const LinkAudit& l) {
  std::set<FindingCode> out;
  for (const Finding& f : l.findings) {
    if (f.severity == Severity::kError) out.insert(f.code);
  }
  return out;
}

/// One shared cache of meshes for every audit of the test.
const std::shared_ptr<AuditMeshCache>& Cache() {
  static const std::shared_ptr<AuditMeshCache> cache = MakeAuditMeshCache(LoadMeshTriangles);
  return cache;
}

RobotAudit Audit(const RobotModel& m) {
  AuditOptions o;
  o.cache = Cache();
  return AuditRobot(m, o);
}

/// The fixes --fix writes (one per link with an error and a fix).
std::vector<InertialRewrite> Fixes(const RobotAudit& a) {
  std::vector<InertialRewrite> out;
  for (std::size_t i = 0; i < a.links.size(); ++i) {
    const Finding* f = FixToApply(a.links[i]);
    if (!f) continue;
    out.push_back({i, f->fix->mass(), f->fix->p_BoBcm_B(), f->fix->I_BBcm_B().matrix(), "fix"});
  }
  return out;
}

/// Replaces the texts of `spans` (from the end) by `texts`.
std::string Splice(std::string text, std::vector<std::pair<TextSpan, std::string>> edits) {
  std::sort(edits.begin(), edits.end(),
            [](const auto& a, const auto& b) { return a.first.offset > b.first.offset; });
  for (const auto& [span, t] : edits) text.replace(span.offset, span.length, t);
  return text;
}

/// A defect: the text with it, or "" when the link cannot carry it.
using Injector = std::function<std::string(const Clean&, std::size_t link, std::mt19937&)>;

/// A rewrite of link `i` to mass `m`, centre of mass `c` and tensor `I` (in L).
std::string Rewrite(const Clean& c, std::size_t i, double m, const Vec3& com, const Mat3& I) {
  return RewriteInertials(c.model, {{i, m, com, I, "injected"}});
}

const LinkAudit& L(const Clean& c, std::size_t i) {
  return c.audit.links[i];
}
bool Geometry(const Clean& c, std::size_t i) {
  return L(c, i).computed.has_value();
}
MassProperties Expected(const Clean& c, std::size_t i) {
  return L(c, i).estimates[*L(c, i).computed].AtMass(L(c, i).given.mass());
}
/// The factor between a tensor and the link's geometry at its mass.
double Factor(const Clean& c, std::size_t i, const Mat3& I) {
  return internal::TensorFactor(I, Expected(c, i).I_BBcm_B().matrix());
}

std::map<FindingCode, Injector> Injectors() {
  std::map<FindingCode, Injector> in;
  auto given = [](const Clean& c, std::size_t i) { return L(c, i).given; };
  in[FindingCode::kNotPositiveDefinite] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    // The smallest principal moment made negative.
    const Eigen::SelfAdjointEigenSolver<Mat3> es(given(c, i).I_BBcm_B().matrix());
    Vec3 l = es.eigenvalues();
    l[0] = -l[0];
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose());
  };
  in[FindingCode::kTriangleInequality] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    const Eigen::SelfAdjointEigenSolver<Mat3> es(given(c, i).I_BBcm_B().matrix());
    Vec3 l = es.eigenvalues();
    l[2] = 1.5 * (l[0] + l[1]);
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose());
  };
  in[FindingCode::kZeroMass] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    if (c.model.links[i].geometries.empty()) return std::string();
    return Rewrite(c, i, 0.0, given(c, i).p_BoBcm_B(), Mat3::Zero());
  };
  in[FindingCode::kMissingInertial] = [](const Clean& c, std::size_t i, std::mt19937&) {
    if (c.model.links[i].geometries.empty()) return std::string();
    // The element removed: MJCF's <inertial .../> ends its start tag, URDF's and SDF's end at
    // </inertial>.
    const InertialText& t = c.model.links[i].inertial.text;
    const bool empty = c.model.text.compare(t.start_tag_end - 2, 2, "/>") == 0;
    const std::size_t end =
        empty ? t.start_tag_end : c.model.text.find("</inertial>", t.element_begin) + 11;
    return Splice(c.model.text, {{TextSpan{t.element_begin, end - t.element_begin}, ""}});
  };
  in[FindingCode::kPlaceholderInertia] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(), 1e-3 * Mat3::Identity());
  };
  in[FindingCode::kImplausibleDensity] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    if (!Geometry(c, i)) return std::string();
    return Rewrite(c, i, 1000 * given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   1000 * given(c, i).I_BBcm_B().matrix());
  };
  in[FindingCode::kRadiusOfGyration] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    if (!Geometry(c, i)) return std::string();
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   1000 * given(c, i).I_BBcm_B().matrix());
  };
  in[FindingCode::kComOutsideGeometry] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    if (!Geometry(c, i)) return std::string();
    const GeometryEstimate& e = L(c, i).estimates[*L(c, i).computed];
    const Vec3 far = e.box_max + (e.box_max - e.box_min);
    return Rewrite(c, i, given(c, i).mass(), far, given(c, i).I_BBcm_B().matrix());
  };
  in[FindingCode::kMismatchGeometry] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    if (!Geometry(c, i)) return std::string();
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   0.03 * given(c, i).I_BBcm_B().matrix());
  };
  in[FindingCode::kDecimalSlip] = [=](const Clean& c, std::size_t i, std::mt19937& rng) {
    if (!Geometry(c, i) || !(Factor(c, i, given(c, i).I_BBcm_B().matrix()) <= 1.4))
      return std::string();
    const RobotInertial& inertial = c.model.links[i].inertial;
    Mat3 W = inertial.I_LcmI_I;
    const int k = static_cast<int>(rng() % 3);
    W(k, k) *= (rng() % 2) ? 100.0 : 0.01;
    const Mat3 I = inertial.R_LI * W * inertial.R_LI.transpose();
    if (!(Factor(c, i, I) > 3.5)) return std::string();
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(), I);
  };
  in[FindingCode::kTransposedEntries] = [=](const Clean& c, std::size_t i, std::mt19937& rng) {
    if (!Geometry(c, i) || !(Factor(c, i, given(c, i).I_BBcm_B().matrix()) <= 1.4))
      return std::string();
    const RobotInertial& inertial = c.model.links[i].inertial;
    Mat3 W = inertial.I_LcmI_I;
    const int a = static_cast<int>(rng() % 3), b = (a + 1 + static_cast<int>(rng() % 2)) % 3;
    std::swap(W(a, a), W(b, b));
    const Mat3 I = inertial.R_LI * W * inertial.R_LI.transpose();
    if (!(Factor(c, i, I) > 3.5)) return std::string();
    return Rewrite(c, i, given(c, i).mass(), given(c, i).p_BoBcm_B(), I);
  };
  in[FindingCode::kSignOfProducts] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    // The geometry's own tensor, its products with the other sign; only where the file writes
    // products (MJCF's diaginertia on its principal axes has none to slip).
    if (!Geometry(c, i) ||
        (c.model.format == RobotFormat::kMjcf && !c.model.links[i].inertial.text.mjcf_full)) {
      return std::string();
    }
    const MassProperties e = Expected(c, i);
    const Mat3 I = e.I_BBcm_B().matrix();
    const Mat3 off = I - Mat3(I.diagonal().asDiagonal());
    const Mat3 wrong = I - 2 * off;
    if (!(off.norm() >= 0.12 * I.trace()) || !(Factor(c, i, wrong) > 1.6) ||
        !e.I_BBcm_B().CheckPhysicallyValid().empty() ||
        !RotationalInertia::FromMatrix(wrong).CheckPhysicallyValid().empty()) {
      return std::string();
    }
    return Rewrite(c, i, e.mass(), e.p_BoBcm_B(), wrong);
  };
  in[FindingCode::kFrame] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    // The geometry's tensor taken about the link origin (eq. 8.29) instead of the centre of mass.
    if (!Geometry(c, i)) return std::string();
    const MassProperties e = Expected(c, i);
    const Vec3 p = e.p_BoBcm_B();
    const Mat3 about_origin =
        e.I_BBcm_B().matrix() + e.mass() * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
    if (!(Factor(c, i, about_origin) > 3.5)) return std::string();
    return Rewrite(c, i, e.mass(), p, about_origin);
  };
  in[FindingCode::kMirrorMismatch] = [=](const Clean& c, std::size_t i, std::mt19937&) {
    const std::string& n = c.model.links[i].name;
    const bool twin =
        std::any_of(c.model.links.begin(), c.model.links.end(), [&](const RobotLink& o) {
          return o.name != n && o.name.size() == n.size() && o.has_inertial &&
                 (n.find("left") != std::string::npos || n.find('L') != std::string::npos) &&
                 std::mismatch(n.begin(), n.end(), o.name.begin()).first != n.end();
        });
    if (!twin) return std::string();
    return Rewrite(c, i, 1.5 * given(c, i).mass(), given(c, i).p_BoBcm_B(),
                   1.5 * given(c, i).I_BBcm_B().matrix());
  };
  in[FindingCode::kDuplicateInertial] = [](const Clean& c, std::size_t i, std::mt19937& rng) {
    // Another link's mass and tensor entries, copied as written (URDF).
    const RobotLink& to = c.model.links[i];
    const std::size_t j = rng() % c.model.links.size();
    const RobotLink& from = c.model.links[j];
    if (j == i || !from.has_inertial || !(from.inertial.mass > 0.0) || !c.errors[j].empty() ||
        c.model.format != RobotFormat::kUrdf || to.inertial.R_LI != from.inertial.R_LI) {
      return std::string();
    }
    std::vector<std::pair<TextSpan, std::string>> edits;
    auto text = [&](const TextSpan& s) { return c.model.text.substr(s.offset, s.length); };
    edits.emplace_back(to.inertial.text.mass, text(from.inertial.text.mass));
    for (int k = 0; k < 6; ++k) {
      edits.emplace_back(to.inertial.text.entries[k], text(from.inertial.text.entries[k]));
    }
    return Splice(c.model.text, edits);
  };
  return in;
}

/// The line a finding on link `i` of `m` may name: the link's, or its inertial's elements'.
bool AtLinkOrInertial(const RobotModel& m, std::size_t i, int line) {
  const RobotLink& l = m.links[i];
  return line == l.line ||
         (l.has_inertial && (line == l.inertial.line || line == l.inertial.mass_line ||
                             line == l.inertial.inertia_line));
}

TEST(AuditInjection, EveryDefectFoundAtItsLinkAndFixed) {
  const std::filesystem::path root =
      std::filesystem::path(chasles::test::SourceDir()) / ".." / "shared" / "robots";
  if (!std::filesystem::is_directory(root)) {
    GTEST_SKIP() << "../shared/robots is absent: no defects injected";
  }
  const std::vector<std::string> files = {
      "example-robot-data/robots/ur_description/urdf/ur5_robot.urdf",
      "example-robot-data/robots/panda_description/urdf/panda.urdf",
      "example-robot-data/robots/panda_description/urdf/panda_collision.urdf",
      "example-robot-data/robots/double_pendulum_description/urdf/double_pendulum_simple.urdf",
      "example-robot-data/robots/solo_description/robots/solo12.urdf",
      "compas_fab/robot_library/abb_irb4600_40_255/urdf/robot_description.urdf",
      "compas_fab/robot_library/ur5_robot/urdf/robot_description.urdf"};
  // And their MJCF and SDF versions (tests/robots; the SDF's meshes as model:// URIs).
  std::vector<std::string> paths;
  for (const std::string& f : files) paths.push_back((root / f).string());
  const std::filesystem::path versions =
      std::filesystem::path(chasles::test::SourceDir()) / "tests/robots";
  for (const char* f :
       {"mjcf/ur5.xml", "mjcf/panda.xml", "mjcf/panda_collision.xml",
        "mjcf/double_pendulum_simple.xml", "mjcf/solo12.xml", "sdf/ur5.sdf", "sdf/panda.sdf",
        "sdf/panda_collision.sdf", "sdf/double_pendulum_simple.sdf", "sdf/solo12.sdf",
        "sdf/abb_irb4600.sdf", "sdf/compas_ur5.sdf"}) {
    paths.push_back((versions / f).string());
  }
  RobotReadOptions read;
  read.packages = {{"example-robot-data", (root / "example-robot-data").string()},
                   {"ur_description", (root / "compas_fab/robot_library/ur_description").string()}};
  std::vector<Clean> robots;
  for (const std::string& f : paths) {
    Clean c;
    c.model = ReadRobotFile(f, read);
    c.audit = Audit(c.model);
    for (const LinkAudit& l : c.audit.links) c.errors.push_back(Errors(l));
    robots.push_back(std::move(c));
  }
  const std::map<FindingCode, Injector> injectors = Injectors();
  std::mt19937 rng(20261128);
  std::map<std::pair<RobotFormat, FindingCode>, int> done;
  const long cases = test::Repeats(1000);
  long made = 0;
  for (long attempt = 0; made < cases && attempt < 50 * cases; ++attempt) {
    const auto it = std::next(injectors.begin(), static_cast<long>(rng() % injectors.size()));
    const FindingCode code = it->first;
    const Clean& c = robots[rng() % robots.size()];
    const std::size_t i = rng() % c.model.links.size();
    const LinkAudit& clean = c.audit.links[i];
    if (!clean.has_inertial || !(clean.given.mass() > 0.0) || !c.errors[i].empty()) continue;
    const std::string text = it->second(c, i, rng);
    if (text.empty()) continue;
    ++made;
    ++done[{c.model.format, code}];
    SCOPED_TRACE(::testing::Message() << FindingCodeName(code) << " at " << c.model.file
                                      << " link '" << clean.name << "'");
    const RobotModel m = ReadRobotBytes(text, c.model.file, read);
    const RobotAudit a = Audit(m);
    bool found = false;
    for (const Finding& f : a.links[i].findings) {
      found = found || (f.code == code && AtLinkOrInertial(m, i, f.line));
    }
    EXPECT_TRUE(found);
    for (std::size_t j = 0; j < a.links.size(); ++j) {
      if (j == i) continue;
      for (const FindingCode e : Errors(a.links[j])) {
        EXPECT_TRUE(c.errors[j].count(e))
            << "new error " << FindingCodeName(e) << " on '" << a.links[j].name << "'";
      }
    }
    // The fix round trip: no error left on the link, none new elsewhere.
    const RobotModel fixed = ReadRobotBytes(RewriteInertials(m, Fixes(a)), c.model.file, read);
    const RobotAudit again = Audit(fixed);
    for (std::size_t j = 0; j < again.links.size(); ++j) {
      for (const FindingCode e : Errors(again.links[j])) {
        EXPECT_TRUE(j != i && c.errors[j].count(e))
            << "after the fix: " << FindingCodeName(e) << " on '" << again.links[j].name << "'";
      }
    }
  }
  EXPECT_GE(made, cases);
  std::map<RobotFormat, int> per_format;
  for (const auto& [key, n] : done) per_format[key.first] += n;
  for (const auto& [format, n] : per_format) RecordProperty(RobotFormatName(format), n);
  // Every class was injected in every format (the codes that need no more than the file
  // itself, and those that need geometry, which the UR5, the Panda and the pendulum have; a
  // copied inertial is written as URDF's text only; MuJoCo wrote every clean MJCF's tensors as
  // diaginertia, without products whose sign could slip). Checked at the full count: the
  // sanitizer build runs a tenth of the cases (test::Repeats), too few to reach every pair.
  if (cases < 1000) return;
  for (const RobotFormat format : {RobotFormat::kUrdf, RobotFormat::kMjcf, RobotFormat::kSdf}) {
    for (const auto& [code, injector] : injectors) {
      if (code == FindingCode::kDuplicateInertial && format != RobotFormat::kUrdf) continue;
      if (code == FindingCode::kSignOfProducts && format == RobotFormat::kMjcf) continue;
      const std::pair<RobotFormat, FindingCode> key{format, code};
      EXPECT_GT(done[key], 0) << FindingCodeName(code) << " never injected in "
                              << RobotFormatName(format);
    }
  }
}

}  // namespace
}  // namespace chasles
