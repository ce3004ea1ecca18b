#pragma once
/// \file povray_scene.h
/// POV-Ray 3.7 scenes of meshes (smooth `mesh2`) and medial surfaces (spheres coloured by
/// radius, hot for small to cold for large, as the paper's Figure 1; a medial mesh as its
/// envelope: the spheres, its edges' cones and its faces' slabs), framed by a View.

#include "core/medial_surface.h"
#include "core/mesh.h"
#include "garbing/target_shape.h"
#include "render/vertex_normals.h"
#include "render/view.h"

#include <string>
#include <variant>
#include <vector>

namespace mg::render {

/// One object of a scene: a mesh (any polygon soup) or a medial surface.
struct SceneObject {
  std::string name;                                   ///< for comments and messages
  std::variant<PolygonSoup, MedialSurface> geometry;  ///< model units
};

/// True if `path` ends in .ma or .xyzr (any case): a medial surface file.
bool has_medial_extension(const std::string& path);

/// Reads a scene object by extension: .off .obj .ply .stl through read_polygon_soup() (the mesh
/// need not be manifold), .ma .xyzr through read_medial_surface(). `name` is the file name.
/// @throws InvalidInput for an unknown extension or a malformed file; IoError if unreadable
SceneObject read_scene_object(const std::string& path);

/// Axis-aligned bounding box: the points of a mesh; the balls (centre +- radius) of atoms. It
/// holds a medial mesh's envelope too: each cone and slab is the convex hull of its balls.
/// @return an empty box for an object without points or atoms
Eigen::AlignedBox3d bounding_box(const SceneObject& object);

/// frame_view() of the object's vertices (mesh) or balls (atoms): the camera looks at the centre
/// of its bounding box from opt.direction, as close as the whole object allows.
/// @throws InvalidInput as frame_view(), prefixed by the object's name
View frame_object(const SceneObject& object, int width, int height, const FramingOptions& opt = {});

/// The colour of an atom, from its radius normalised to t in [0, 1] over the surface's radii:
/// the hue goes from red (t = 0, smallest) through yellow, green and cyan to blue (t = 1,
/// largest), full saturation and value. Linear RGB in [0, 1]. t is clamped to [0, 1].
Eigen::Vector3d radius_colour(double t);

/// Options of povray_scene().
struct SceneOptions {
  bool flat_shading = false;  ///< meshes without normals: every triangle flat
  /// Weighting and crease angle of smooth shading: angle-weighted, edges sharper than 60
  /// degrees stay sharp (a cube looks like a cube; smooth models are not affected).
  NormalOptions normals{NormalWeighting::angle, /*crease_angle=*/60.0};
  /// Fraction of light passing through meshes, [0, 1): 0 opaque; e.g. 0.6 shows the atoms of a
  /// medial surface rendered inside the original object.
  double mesh_transmit = 0.0;
  int colour_levels = 256;  ///< atom colours are quantised to this many shared textures, >= 2
  /// What a medial surface shows: `envelope` ("ma") its balls, one cone per distinct edge and
  /// one slab per distinct face (garbing::envelope_primitives()); `atoms` ("rt") its balls
  /// alone, edges and faces ignored; `automatic`: the envelope when it has edges or faces.
  garbing::PrimitiveSet primitives = garbing::PrimitiveSet::automatic;
};

/// The complete text of a POV-Ray 3.7 scene: camera from `view` (image aspect from its width
/// and height), a white background, a key light with shadows, a fill and a rim light placed
/// relative to the camera, then every object (smooth meshes cast no shadow: smooth triangles
/// would shadow their neighbours along a jagged terminator). Meshes become `mesh2` (polygons
/// fan-triangulated, per-corner normals from shading_normals() unless flat), coloured from a fixed
/// palette by their rank among the meshes; medial surfaces a union of spheres coloured by
/// radius_colour() (quantised to opt.colour_levels). A medial mesh drawn as its envelope
/// (opt.primitives) adds, after its spheres, each cone's lateral surface (an open `cone` from
/// tangent circle to tangent circle, a gradient pigment along its axis) and one flat `mesh2` of
/// every slab's two tangent triangles (per-corner textures, each triangle first cut where its
/// colours cross a bend of the colour map). Every point of a cone or slab takes the colour of
/// the interpolated ball touching it there: radius_colour() of that ball's value of t, which is
/// its atoms' quantised values interpolated linearly, so colours run on without a seam from
/// ball to cone to slab. Cones of zero width or radius and slabs without tangent triangles add
/// nothing to the balls and are left out. Without edges and faces, or with `atoms`, the text is
/// that of the spheres alone: the same as for the atoms without their edges and faces. The text
/// depends only on the arguments (numbers printed in the "C" locale).
/// @pre validate(view) holds; every face index in range; atoms valid (validate())
/// @throws InvalidInput naming the object or option at fault
std::string povray_scene(const std::vector<SceneObject>& objects, const View& view,
                         const SceneOptions& opt = {});

/// The `camera { ... }` block of povray_scene() alone (identical text for identical views).
std::string povray_camera(const View& view);

}  // namespace mg::render
