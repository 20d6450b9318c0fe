// Tiled terrains ("tiles" on a terrain mesh): one large mesh drawn as a grid
// of smaller ones, so that the engine culls each tile on its own and a
// level-of-detail policy gives near and far tiles different levels, with
// bakes of their own. Done once, when the scene file is read, so that every
// later stage sees ordinary meshes and instances.
#pragma once

#include "scene/scene_file.h"
#include "support/diagnostic.h"

namespace spire::scene {

// The name of tile (x, z) of mesh `mesh`: "hills[2,5]".
std::string tileMeshName(const std::string& mesh, uint32_t x, uint32_t z);

// Adds the tile meshes of every mesh with tiles > 1 and replaces each
// instance of such a mesh, in place and in row order, by one instance per
// tile with the same shader, material and transform. The whole mesh stays
// defined (a scatter may place copies on it). A tile name that is already a
// mesh's is reported (E7007) at that mesh.
void splitTiles(SceneFile& scene, DiagnosticList& diags);

}  // namespace spire::scene
