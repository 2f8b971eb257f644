// `stratad export-scene NAME OUT.glb` and `stratad list-scenes`.
#include <iostream>
#include <string>

#include "cli/commands.h"
#include "scene/scene_io.h"

namespace strata::cli {

Runner add_export_scene_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("export-scene", "write a built-in scene as .glb (with LoDs and its default animation)");
  auto name = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("name", *name, "built-in scene name")->required();
  cmd->add_option("out", *out, "output .glb path")->required();
  return [=] {
    scene::Scene s = scene::builtin_scene(*name);
    scene::export_glb_file(s, *out);
    std::cout << "wrote " << *out << " (" << s.triangle_count() << " triangles, " << s.instances.size() << " instances)\n";
    return 0;
  };
}

Runner add_list_scenes_command(CLI::App& app) {
  app.add_subcommand("list-scenes", "list the built-in scenes");
  return [] {
    for (const auto& n : scene::builtin_scene_names()) {
      scene::Scene s = scene::builtin_scene(n);
      std::cout << n << "\t" << s.triangle_count() << " triangles\t" << s.instances.size() << " instances\n";
    }
    return 0;
  };
}

}  // namespace strata::cli
