// Mesh URIs of robot files (files/internal/package_path.h).

#include "files/internal/package_path.h"

#include <filesystem>
#include <system_error>

#include <fmt/format.h>

namespace chasles::internal {

namespace fs = std::filesystem;

namespace {

/// True when the lexically normal `path` lies inside the lexically normal `root`.
bool Inside(const fs::path& path, const fs::path& root) {
  auto p = path.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++p) {
    if (r->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *r) return false;
  }
  return true;
}

fs::path Absolute(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

/// The robot's own tree: the nearest folder above the file that holds a package.xml, else
/// the folder above the file's folder (the usual urdf/ beside meshes/).
fs::path RobotRoot(const fs::path& robot_file) {
  const fs::path folder = Absolute(robot_file).parent_path();
  std::error_code ec;
  for (fs::path d = folder; !d.empty(); d = d.parent_path()) {
    if (fs::exists(d / "package.xml", ec)) return d;
    if (d == d.root_path()) break;
  }
  return folder.has_parent_path() ? folder.parent_path() : folder;
}

/// The folder of package `name`: given, else a folder above the robot file named so or holding
/// a folder so named.
fs::path FindPackage(const std::string& name, const fs::path& robot_file,
                     const PackageDirs& packages) {
  for (const auto& [n, dir] : packages) {
    if (n == name) return Absolute(dir);
  }
  std::error_code ec;
  for (fs::path d = Absolute(robot_file).parent_path(); !d.empty(); d = d.parent_path()) {
    if (d.filename() == name) return d;
    if (fs::is_directory(d / name, ec)) return d / name;
    if (d == d.root_path()) break;
  }
  return {};
}

/// Why `path` may not be read: a device, a special file, a system folder.
std::string DeviceProblem(const fs::path& path) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(path, ec);
  const fs::path p = ec ? path : real;
  for (const char* system : {"/dev", "/proc", "/sys"}) {
    if (Inside(p, system)) return fmt::format("it points into {}", system);
  }
  const fs::file_status st = fs::status(p, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st)) {
    return "it is not a regular file (a folder, a device or a pipe)";
  }
  return "";
}

}  // namespace

ResolvedPath ResolveUriOrRefuse(const std::string& uri, const std::string& robot_file,
                                const std::string& base_dir, const PackageDirs& packages,
                                std::string* refusal) {
  constexpr std::string_view kPackage = "package://", kFile = "file://";
  fs::path path;
  fs::path root;
  if (uri.starts_with(kPackage)) {
    const std::string rest = uri.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == 0 || slash == std::string::npos || slash + 1 == rest.size()) {
      *refusal = fmt::format("mesh URI '{}': expected package://NAME/PATH", uri);
      return {};
    }
    const std::string name = rest.substr(0, slash);
    const fs::path inner = rest.substr(slash + 1);
    if (inner.is_absolute() || inner.has_root_name()) {
      *refusal = fmt::format("mesh URI '{}': the path inside the package is absolute", uri);
      return {};
    }
    if (const fs::path n = inner.lexically_normal(); !n.empty() && *n.begin() == "..") {
      *refusal = fmt::format("mesh URI '{}' climbs out of its package '{}'", uri, name);
      return {};
    }
    root = FindPackage(name, robot_file, packages);
    if (root.empty()) {
      return {"", fmt::format("package '{}' not found above the robot file (give --package "
                              "{}=DIR)",
                              name, name)};
    }
    path = (root / inner).lexically_normal();
    if (!Inside(path, root)) {
      *refusal = fmt::format("mesh URI '{}' climbs out of its package '{}'", uri, root.string());
      return {};
    }
  } else {
    fs::path p = uri.starts_with(kFile) ? fs::path(uri.substr(kFile.size())) : fs::path(uri);
    if (uri.find("://") != std::string::npos && !uri.starts_with(kFile)) {
      *refusal =
          fmt::format("mesh URI '{}': only package://, file:// and file paths are read", uri);
      return {};
    }
    if (p.empty()) {
      *refusal = "an empty mesh file name";
      return {};
    }
    const fs::path base =
        base_dir.empty() ? Absolute(robot_file).parent_path() : Absolute(base_dir);
    path = p.is_absolute() ? p.lexically_normal() : (base / p).lexically_normal();
    root = RobotRoot(robot_file);
    if (!p.is_absolute() && !Inside(path, root)) {
      *refusal =
          fmt::format("mesh path '{}' climbs out of the robot's folder '{}'", uri, root.string());
      return {};
    }
  }
  const std::string device = DeviceProblem(path);
  if (!device.empty()) {
    *refusal = fmt::format("mesh URI '{}' cannot be read: {}", uri, device);
    return {};
  }
  std::error_code ec;
  if (!fs::exists(path, ec)) return {"", fmt::format("mesh file '{}' not found", path.string())};
  return {path.string(), ""};
}

}  // namespace chasles::internal
