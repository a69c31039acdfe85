// m4d scene: writes the built-in synthetic multi-view scene to a directory.
#ifndef M4D_TOOLS_M4D_SCENE_COMMAND_H_
#define M4D_TOOLS_M4D_SCENE_COMMAND_H_

#include <CLI/CLI.hpp>

namespace m4d {

void AddSceneCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_SCENE_COMMAND_H_
