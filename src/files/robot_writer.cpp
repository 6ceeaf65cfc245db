// Corrected inertials written back in the file's own syntax (chasles/files/robot_writer.h).

#include "chasles/files/robot_writer.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/error.h"

namespace chasles {

namespace {

/// A replacement of the bytes [offset, offset + length).
struct Edit {
  std::size_t offset, length;
  std::string text;
};

std::string Num(double v) {
  const std::string s = fmt::format("{:.6g}", v);
  return s == "-0" ? "0" : s;
}

std::string Nums(std::initializer_list<double> v) {
  std::string out;
  for (const double x : v) {
    if (!out.empty()) out += ' ';
    out += Num(x);
  }
  return out;
}

class Writer {
 public:
  Writer(const RobotModel& model, std::vector<Edit>& edits) : model_(model), edits_(edits) {}
  void Apply(const InertialRewrite& fix);

 private:
  /// Replaces the text at `span` with `text` when the printed value differs.
  void Put(const TextSpan& span, const std::string& text, const std::string& old_text,
           const char* what) {
    if (text == old_text) return;
    if (!span.found()) Fail(what);
    edits_.push_back({span.offset, span.length, text});
  }
  [[noreturn]] void Fail(const char* what) const {
    throw InputError(fmt::format("{}: link '{}': its {} has no text in the file to rewrite",
                                 model_.file, link_->name, what));
  }
  void Urdf(const InertialRewrite& fix, const RobotInertial& in);
  void Mjcf(const InertialRewrite& fix, const RobotInertial& in);
  void Sdf(const InertialRewrite& fix, const RobotInertial& in);
  void Comment(const RobotInertial& in, const std::string& text);

  const RobotModel& model_;
  std::vector<Edit>& edits_;
  const RobotLink* link_ = nullptr;
};

void Writer::Urdf(const InertialRewrite& fix, const RobotInertial& in) {
  const Vec3& c = fix.p_LoLcm_L;
  const Vec3& c0 = in.p_LoLcm_L;
  if (Nums({c.x(), c.y(), c.z()}) != Nums({c0.x(), c0.y(), c0.z()})) {
    if (in.text.position.found()) {
      edits_.push_back(
          {in.text.position.offset, in.text.position.length, Nums({c.x(), c.y(), c.z()})});
    } else {
      // No <origin xyz>: one is inserted first in the <inertial> (rpy absent: identity).
      if (in.text.orientation.found()) Fail("centre of mass (an <origin> with rpy only)");
      edits_.push_back({in.text.start_tag_end, 0,
                        fmt::format("<origin xyz=\"{}\"/>", Nums({c.x(), c.y(), c.z()}))});
    }
  }
  Put(in.text.mass, Num(fix.mass), Num(in.mass), "mass");
  const Mat3 W = in.R_LI.transpose() * fix.I_LcmL_L * in.R_LI;  // into the file's frame I
  static constexpr int kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 6; ++k) {
    Put(in.text.entries[k], Num(W(kRow[k], kCol[k])), Num(in.I_LcmI_I(kRow[k], kCol[k])),
        "inertia");
  }
}

void Writer::Sdf(const InertialRewrite& fix, const RobotInertial& in) {
  const Vec3& c = fix.p_LoLcm_L;
  const Vec3& c0 = in.p_LoLcm_L;
  if (Nums({c.x(), c.y(), c.z()}) != Nums({c0.x(), c0.y(), c0.z()})) {
    // The pose's text: the position replaced, its rotation (three or four numbers) kept.
    const TextSpan& s = in.text.position;
    if (!s.found()) {
      edits_.push_back({in.text.start_tag_end, 0,
                        fmt::format("<pose>{} 0 0 0</pose>", Nums({c.x(), c.y(), c.z()}))});
    } else {
      std::string_view text = std::string_view(model_.text).substr(s.offset, s.length);
      std::size_t at = 0;
      for (int k = 0; k < 3; ++k) {
        at = text.find_first_not_of(" \t\r\n", at);
        at = text.find_first_of(" \t\r\n", at);
      }
      const std::string rest = at == std::string_view::npos ? "" : std::string(text.substr(at));
      edits_.push_back({s.offset, s.length, Nums({c.x(), c.y(), c.z()}) + rest});
    }
  }
  Put(in.text.mass, Num(fix.mass), Num(in.mass), "mass");
  const Mat3 W = in.R_LI.transpose() * fix.I_LcmL_L * in.R_LI;
  static constexpr int kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 6; ++k) {
    Put(in.text.entries[k], Num(W(kRow[k], kCol[k])), Num(in.I_LcmI_I(kRow[k], kCol[k])),
        "inertia");
  }
}

void Writer::Mjcf(const InertialRewrite& fix, const RobotInertial& in) {
  const Vec3& c = fix.p_LoLcm_L;
  const Vec3& c0 = in.p_LoLcm_L;
  Put(in.text.position, Nums({c.x(), c.y(), c.z()}), Nums({c0.x(), c0.y(), c0.z()}), "pos");
  Put(in.text.mass, Num(fix.mass), Num(in.mass), "mass");
  const Mat3& I = fix.I_LcmL_L;
  if (in.text.mjcf_full) {
    Put(in.text.mjcf_inertia, Nums({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}),
        Nums({in.I_LcmI_I(0, 0), in.I_LcmI_I(1, 1), in.I_LcmI_I(2, 2), in.I_LcmI_I(0, 1),
              in.I_LcmI_I(0, 2), in.I_LcmI_I(1, 2)}),
        "fullinertia");
    return;
  }
  const Vec3 d0 = in.I_LcmI_I.diagonal();
  const Mat3 W = in.R_LI.transpose() * I * in.R_LI;
  const double off = (W - Mat3(W.diagonal().asDiagonal())).norm();
  if (off <= 1e-9 * W.norm()) {
    Put(in.text.mjcf_inertia, Nums({W(0, 0), W(1, 1), W(2, 2)}), Nums({d0.x(), d0.y(), d0.z()}),
        "diaginertia");
    return;
  }
  // The principal moments on their axes: a quat replaces the orientation attribute.
  const Eigen::SelfAdjointEigenSolver<Mat3> es(I);
  Mat3 R = es.eigenvectors();
  if (R.determinant() < 0) R.col(2) = -R.col(2);
  const Quat q(R);
  const Vec3 m = es.eigenvalues();
  Put(in.text.mjcf_inertia, Nums({m.x(), m.y(), m.z()}), "", "diaginertia");
  const std::string quat = fmt::format("quat=\"{}\"", Nums({q.w(), q.x(), q.y(), q.z()}));
  if (in.text.orientation.found()) {
    // `key="value"` as a whole: from the key to the closing quote.
    const std::string& key = in.text.orientation_key;
    const std::size_t name = model_.text.rfind(key, in.text.orientation.offset);
    const std::size_t close =
        model_.text.find_first_of("\"'", in.text.orientation.offset + in.text.orientation.length);
    if (name == std::string::npos || close == std::string::npos) Fail("orientation");
    edits_.push_back({name, close + 1 - name, quat});
  } else {
    if (!in.text.position.found()) Fail("pos");
    const std::size_t close =
        model_.text.find_first_of("\"'", in.text.position.offset + in.text.position.length);
    if (close == std::string::npos) Fail("pos");
    edits_.push_back({close + 1, 0, " " + quat});
  }
}

void Writer::Comment(const RobotInertial& in, const std::string& text) {
  if (in.text.element_begin == TextSpan::kNone) return;
  const std::size_t line_start = model_.text.rfind('\n', in.text.element_begin);
  const std::size_t from = line_start == std::string::npos ? 0 : line_start + 1;
  std::string indent = model_.text.substr(from, in.text.element_begin - from);
  if (indent.find_first_not_of(" \t") != std::string::npos) indent = " ";
  std::string body;  // "--" may not appear in an XML comment
  for (const char ch : text) {
    if (ch == '-' && !body.empty() && body.back() == '-') body += ' ';
    body += ch;
  }
  const std::string sep = indent == " " ? " " : "\n" + indent;
  edits_.push_back(
      {in.text.element_begin, 0, fmt::format("<!-- chasles audit: {} -->{}", body, sep)});
}

void Writer::Apply(const InertialRewrite& fix) {
  link_ = &model_.links.at(fix.link);
  if (!link_->has_inertial) {
    throw InputError(
        fmt::format("{}: link '{}' has no inertial to rewrite", model_.file, link_->name));
  }
  const RobotInertial& in = link_->inertial;
  const std::size_t before = edits_.size();
  switch (model_.format) {
    case RobotFormat::kUrdf:
      Urdf(fix, in);
      break;
    case RobotFormat::kMjcf:
      Mjcf(fix, in);
      break;
    case RobotFormat::kSdf:
      Sdf(fix, in);
      break;
  }
  if (edits_.size() > before) Comment(in, fix.comment);
}

}  // namespace

std::string RewriteInertials(const RobotModel& model, const std::vector<InertialRewrite>& fixes) {
  std::vector<Edit> edits;
  Writer writer(model, edits);
  for (const InertialRewrite& f : fixes) writer.Apply(f);
  // From the end, so that earlier offsets stay valid; an insertion before a replacement at the
  // same offset.
  std::stable_sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
    return a.offset != b.offset ? a.offset > b.offset : a.length > b.length;
  });
  std::string out = model.text;
  for (const Edit& e : edits) out.replace(e.offset, e.length, e.text);
  return out;
}

}  // namespace chasles
