#include <string>

#include <fmt/format.h>

#include "chasles/mass/materials.h"
#include "commands.h"

namespace chasles::cli {

CLI::App* AddMaterialsCommand(CLI::App& app) {
  return app.add_subcommand("materials",
                            "List the built-in materials and their densities (kg/m^3)");
}

int RunMaterials() {
  fmt::print(
      "Built-in materials: typical room-temperature handbook densities. A scene can define "
      "its own under 'materials:'.\n");
  for (const Material& m : Materials()) {
    std::string aliases;
    for (std::string_view a : m.aliases)
      aliases += (aliases.empty() ? "also " : ", ") + std::string(a);
    fmt::print("  {:<20} {:>8g} kg/m^3  {}\n", m.name, m.density, aliases);
  }
  return 0;
}

}  // namespace chasles::cli
