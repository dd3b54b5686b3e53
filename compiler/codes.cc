// The catalogue of diagnostic codes, for `efc explain CODE`. Codes are stable:
// never renumber or reuse one; add new ones at the end of their range.
//
//   E00xx  the file itself: I/O, encoding, JSON syntax
//   E01xx  document shape: types, required/unknown keys, names, enums, paths, meshes
//   E02xx  parts and joints: the part tree, joint values, geometry sizes
//   E03xx  functions: references, the function graph, mappings, effects
//   E09xx  backends and output
//   E10xx  sequence folders (shared/spec/sequence.md)
//   E11xx  efc batch: manifests, job results, shards, Slurm
//   Wxxxx  warnings, numbered like the errors of the same area
#include <algorithm>
#include <cctype>

#include "compiler/diagnostics.h"

namespace efc {

const std::vector<CodeInfo>& all_codes() {
  static const std::vector<CodeInfo> codes = {
      // ---------------------------------------------------------------- E00xx
      {"E0001", "cannot read the file",
       "The spec file could not be opened or read: it does not exist, is a folder, or\n"
       "is not readable. The command exits with code 2.\n"
       "  efc check exmaples/lamp.json\n"
       "Fix: check the path and the file's permissions."},
      {"E0002", "the file is empty",
       "The file holds nothing but whitespace. A spec is one JSON object.\n"
       "Fix: write at least {\"efc\": 1, \"name\": \"thing\", \"parts\": [...]}."},
      {"E0003", "JSON syntax error",
       "The file is not valid JSON; the position is where parsing failed. Common\n"
       "causes: a trailing comma, a missing comma or bracket, a truncated file,\n"
       "comments, single quotes.\n"
       "  {\"efc\": 1, \"parts\": [ {...}, ]}     <- trailing comma\n"
       "Fix: correct the syntax at the reported position (a JSON linter helps)."},
      {"E0004", "the file is not UTF-8 text",
       "The file contains bytes that are not well-formed UTF-8 (often a binary file,\n"
       "or text saved in Latin-1). The position is the first bad byte.\n"
       "Fix: save the spec as UTF-8, or check that you passed the right file."},
      {"E0005", "nesting too deep",
       "Arrays and objects are nested deeper than the reader allows (256 levels).\n"
       "A spec needs fewer than ten; the reader stops instead of risking a crash.\n"
       "  {\"x-data\": [[[[[[ ... 300 levels ... ]]]]]]}\n"
       "Fix: this file is probably not a spec; flatten the data."},
      {"E0006", "number out of range",
       "A number does not fit a double (it overflows to infinity), or is not finite.\n"
       "  \"mass\": 1e999\n"
       "Fix: write a finite number; SI values in a spec are far below 1e308."},
      {"E0007", "duplicate key",
       "The same key appears twice in one JSON object. JSON tools disagree on which\n"
       "value wins, so efc refuses both.\n"
       "  {\"name\": \"lid\", \"mass\": 0.2, \"mass\": 0.3}\n"
       "Fix: keep one of them."},
      {"E0010", "DSL syntax error",
       "A .efc file does not follow the grammar (grammar/efc.ebnf) at the reported\n"
       "position: a missing '{' or '}', a missing comma in a vector, two statements\n"
       "on one line without ';', a value where a field name belongs. The parser\n"
       "goes on at the next statement, so every syntax error is listed at once.\n"
       "  box { size (1, 2 3) cm }          <- missing ','\n"
       "  box { size 1 } mass 2             <- missing ';' or line break\n"
       "Fix: correct the syntax at the caret; `efc fmt` shows the canonical layout."},
      {"E0011", "invalid token",
       "A .efc file holds something that is not a token of the language: an\n"
       "unterminated string, an unknown escape, a number like 1. or 01, a character\n"
       "such as @ or a single quote.\n"
       "  description \"a lamp            <- the string is not closed on its line\n"
       "Fix: close strings on the line they start; numbers are written as in JSON."},
      {"E0012", "unknown unit",
       "A number in a .efc file is followed by a word that is not a unit. Units:\n"
       "m cm mm (lengths), rad deg (angles), kg, s, C K (temperature), lm (light),\n"
       "L/min (liquid flow), m/s (speed). A bare number is in the field's SI unit.\n"
       "  mass 3 kgs\n"
       "Fix: write one of the units above (mass 3 kg), or none."},
      // ---------------------------------------------------------------- E01xx
      {"E0101", "wrong type",
       "A value has the wrong JSON type: a string where a number is expected, an\n"
       "object where an array is expected, and so on. The document itself must be\n"
       "an object.\n"
       "  \"mass\": \"0.2\"\n"
       "Fix: write the type the spec asks for (\"mass\": 0.2)."},
      {"E0102", "missing required field",
       "A required field is absent. Required: efc, name, parts (top level); name and\n"
       "geometry (part); type and parent (joint); name, receptor, effector, mapping,\n"
       "effect (function); type (mapping, effect); size (box); radius (sphere,\n"
       "cylinder); length (cylinder); stiffness (spring).\n"
       "  {\"type\": \"revolute\", \"range\": [0, 1]}      <- joint without \"parent\"\n"
       "Fix: add the field."},
      {"E0103", "unknown key",
       "A key the spec does not define at this place. Keys that start with \"x-\" are\n"
       "allowed anywhere and ignored (kept for tools). Mapping and effect keys depend\n"
       "on the type: \"gain\" belongs to a linear mapping, not a binary one; \"scale\"\n"
       "applies only to a mesh; a fixed joint takes no initial, damping, friction or\n"
       "spring.\n"
       "  {\"type\": \"revolute\", \"parnet\": \"body\"}\n"
       "Fix: correct the spelling (the hint suggests the closest key), or prefix the\n"
       "key with x- to keep private data."},
      {"E0104", "unsupported format version",
       "The \"efc\" field must be the integer 1 (this compiler reads spec version 1).\n"
       "  \"efc\": 2\n"
       "Fix: write \"efc\": 1, or use a compiler that reads the newer version."},
      {"E0105", "invalid name",
       "Names of the object, parts and functions must match\n"
       "^[A-Za-z_][A-Za-z0-9_]{0,63}$: letters, digits and underscores, not starting\n"
       "with a digit, at most 64 characters. They become MuJoCo/URDF element names,\n"
       "C++ identifiers and Python identifiers, so quotes, spaces, '<', '-' or '.'\n"
       "would break generated code.\n"
       "  \"name\": \"left door\"\n"
       "Fix: use \"left_door\"."},
      {"E0106", "reserved name prefix",
       "Names may not start with \"efc_\": the compiler gives that prefix to the\n"
       "elements it generates (e.g. MuJoCo sites, actuators and sensors named\n"
       "efc_<part>_...), so a user name with it could collide with them.\n"
       "  \"name\": \"efc_button\"\n"
       "Fix: choose another name, e.g. \"button\"."},
      {"E0107", "unknown enumeration value",
       "A field that takes one of a fixed set of words has another value.\n"
       "  role: base, receptor, effector, other\n"
       "  joint type: fixed, revolute, continuous, prismatic\n"
       "  mapping type: binary, step, linear, cumulative\n"
       "  effect type: geometry, illumination, temperature, fluid, airflow\n"
       "  \"type\": \"hinge\"\n"
       "Fix: use one of the listed words (\"revolute\")."},
      {"E0108", "geometry needs exactly one kind",
       "A GEOMETRY object must have exactly one of mesh, box, cylinder, sphere,\n"
       "compound.\n"
       "  \"geometry\": {\"box\": {...}, \"sphere\": {...}}\n"
       "Fix: keep one; a part made of several pieces uses\n"
       "\"compound\": [{\"box\": ...}, {\"sphere\": ...}]."},
      {"E0109", "wrong array length",
       "A fixed-length array has the wrong number of elements: vectors (center,\n"
       "axis, origin, position, direction, size, rpy, scale, color) take 3 numbers,\n"
       "ranges 2, rgba 4.\n"
       "  \"axis\": [0, 1]\n"
       "Fix: give every component (\"axis\": [0, 1, 0])."},
      {"E0110", "colour component outside [0, 1]",
       "rgba and light colours are fractions in [0, 1], not 0..255.\n"
       "  \"rgba\": [255, 128, 0, 1]\n"
       "Fix: divide by 255 (\"rgba\": [1.0, 0.5, 0.0, 1.0])."},
      {"E0111", "mesh file cannot be loaded",
       "The mesh file exists but could not be read as a mesh: a corrupt or empty\n"
       "file, an unsupported variant of the format, or no triangles.\n"
       "Fix: re-export the mesh (OBJ, STL or PLY with triangles) and check it opens\n"
       "in a viewer."},
      {"E0112", "mesh path leaves the spec's folder",
       "Relative paths resolve against the folder that holds the spec and may not\n"
       "climb out of it with \"..\", so a spec cannot make the compiler read files\n"
       "elsewhere (the check is on the path as written; symlinks are not followed).\n"
       "  \"mesh\": \"../../shared/handle.obj\"\n"
       "Fix: copy the mesh next to the spec (e.g. meshes/handle.obj)."},
      {"E0113", "absolute mesh path",
       "Mesh paths must be relative to the spec's folder, so a spec folder can be\n"
       "moved and shared. Absolute paths are accepted only with\n"
       "--allow-absolute-paths.\n"
       "  \"mesh\": \"/home/me/handle.obj\"\n"
       "Fix: write the path relative to the spec, or pass --allow-absolute-paths."},
      {"E0114", "unsupported mesh file type",
       "Meshes must be .obj, .stl or .ply files (any letter case).\n"
       "  \"mesh\": \"meshes/handle.fbx\"\n"
       "Fix: convert the mesh to one of those formats."},
      {"E0115", "mesh file not found",
       "The mesh path is well-formed but no file exists there (relative to the\n"
       "spec's folder). The message shows the absolute path that was tried.\n"
       "  \"mesh\": \"meshes/hadle.obj\"\n"
       "Fix: correct the path or add the file."},
      {"E0116", "empty list",
       "A list that needs at least one element is empty: \"parts\" (an object has at\n"
       "least its root part) and \"compound\" (at least one piece).\n"
       "  \"parts\": []\n"
       "Fix: add the elements."},
      {"E0120", "geometry encloses no volume",
       "A part's geometry has zero volume (a flat mesh with no convex hull, for\n"
       "example), so it has no inertia a simulator could use.\n"
       "Fix: give the part a solid shape."},
      {"E0131", "unit does not fit the field",
       "A .efc number carries a unit of the wrong kind for its field: a mass where an\n"
       "angle belongs, a length on a revolute joint's range, any unit on a unitless\n"
       "field (axis, direction, colours, gain, stiffness). Joint positions are\n"
       "angles for revolute and continuous joints and lengths for prismatic ones; a\n"
       "mapping's threshold follows its receptor's joint, an effect range its effect.\n"
       "  joint revolute on base { range 0 .. 40 mm }\n"
       "  mapping step { threshold 3 kg }\n"
       "Fix: write the number in a unit the message lists, or bare (SI)."},
      // ---------------------------------------------------------------- E02xx
      {"E0201", "no root part",
       "Every part has a joint, so nothing is fixed to the world. Exactly one part,\n"
       "the root, has no joint.\n"
       "Fix: remove the joint of the part that stands still (usually the base)."},
      {"E0202", "several root parts",
       "More than one part has no joint. Exactly one part is the root; every other\n"
       "part hangs from a parent through a joint.\n"
       "  {\"name\": \"base\", ...}, {\"name\": \"lid\", ...}    <- neither has a joint\n"
       "Fix: give the extra part a joint; \"type\": \"fixed\" attaches it rigidly."},
      {"E0203", "joint range not ordered",
       "A joint range [lo, hi] must have lo < hi (radians for revolute, metres for\n"
       "prismatic). Joint position 0 need not lie inside it.\n"
       "  \"range\": [1.2, 0.3]\n"
       "Fix: swap the two numbers (\"range\": [0.3, 1.2])."},
      {"E0204", "unknown parent",
       "A joint's \"parent\" names no part of the object.\n"
       "  \"parent\": \"bdoy\"\n"
       "Fix: use the name of an existing part (the hint suggests the closest one)."},
      {"E0205", "part is its own parent",
       "A joint's \"parent\" is the part that owns the joint.\n"
       "Fix: name the part it is mounted on."},
      {"E0206", "parents form a cycle",
       "Following parents from some part comes back to it (a -> b -> a), so the parts\n"
       "do not form a tree hanging from the root.\n"
       "Fix: make one of the parts in the loop hang from a part outside it."},
      {"E0207", "duplicate part name",
       "Two parts have the same name; names identify parts in joints, functions and\n"
       "generated files.\n"
       "Fix: rename one of them."},
      {"E0208", "joint range missing",
       "Revolute and prismatic joints need \"range\": [lo, hi] (their limits).\n"
       "  {\"type\": \"revolute\", \"parent\": \"body\", \"axis\": [0, 0, 1]}\n"
       "Fix: add the range, or use \"type\": \"continuous\" for a joint that turns\n"
       "without limits."},
      {"E0209", "joint range not allowed",
       "Continuous and fixed joints have no limits, so they take no range.\n"
       "  {\"type\": \"continuous\", \"range\": [0, 6.28], ...}\n"
       "Fix: remove the range, or use \"type\": \"revolute\" for a limited joint."},
      {"E0210", "zero axis",
       "A joint axis or a cylinder axis is [0, 0, 0], which has no direction.\n"
       "Fix: give a direction, e.g. [0, 0, 1]."},
      {"E0211", "axis on a fixed joint",
       "A fixed joint does not move, so an axis means nothing and is rejected (it\n"
       "usually signals the wrong joint type).\n"
       "Fix: remove the axis, or choose a movable joint type."},
      {"E0212", "mass not positive",
       "A part's mass must be > 0 kg.\n"
       "  \"mass\": 0\n"
       "Fix: give the real mass, or leave it out: it is then computed from the\n"
       "geometry's volume at 500 kg/m^3."},
      {"E0213", "geometry size not positive",
       "Box sizes, radii, lengths and mesh scale factors must be > 0.\n"
       "  {\"sphere\": {\"radius\": -0.1}}\n"
       "Fix: use positive sizes in metres (box sizes are full edge lengths)."},
      {"E0214", "negative joint damping or friction, or a spring without stiffness",
       "Joint damping and friction must be >= 0 (negative values inject energy and\n"
       "make the simulation blow up); a spring's stiffness must be > 0.\n"
       "  \"damping\": -0.05\n"
       "Fix: use 0 or a positive value (a positive stiffness, or no spring)."},
      // ---------------------------------------------------------------- E03xx
      {"E0301", "duplicate function name",
       "Two functions have the same name; names label logs, CSV columns and\n"
       "generated code.\n"
       "Fix: rename one of them."},
      {"E0302", "unknown receptor",
       "A function's \"receptor\" names no part.\n"
       "Fix: use the name of the part the user moves."},
      {"E0303", "unknown effector",
       "A function's \"effector\" names no part.\n"
       "Fix: use the name of the part the function acts on."},
      {"E0304", "receptor and effector are the same part",
       "A function maps the receptor's state to an effect on another part; the two\n"
       "must differ.\n"
       "Fix: name the part that shows the effect as the effector."},
      {"E0305", "receptor cannot move",
       "The receptor's state is its joint position, so it needs a movable joint:\n"
       "the root and parts with a fixed joint cannot be receptors.\n"
       "Fix: give the receptor a revolute, continuous or prismatic joint."},
      {"E0306", "geometry effect on a part that cannot move",
       "A geometry effect drives the effector's joint, so the effector needs a\n"
       "movable joint.\n"
       "  effector \"lid\" with {\"type\": \"fixed\"} and effect {\"type\": \"geometry\"}\n"
       "Fix: give the effector a revolute, continuous or prismatic joint."},
      {"E0307", "two functions write the same effect",
       "Two functions set the same effect type on the same effector (e.g. both set\n"
       "the illumination of \"bulb\"), so the result would depend on their order.\n"
       "Fix: merge them, or give each a different effector or effect type."},
      {"E0308", "functions form a cycle",
       "Functions may chain (one function's effector is another's receptor) but the\n"
       "chain may not loop back: a -> b and b -> a would drive each other forever.\n"
       "Fix: remove one function of the loop."},
      {"E0309", "effect range has equal ends",
       "An effect range is [off, on]; the two ends must differ (on may be below off).\n"
       "  \"range\": [0, 0]\n"
       "Fix: give the state at rest and the fully actuated state."},
      {"E0310", "unphysical effect value",
       "Light output (lumens), flow (L/min) and air speed (m/s) cannot be negative;\n"
       "a temperature cannot be below absolute zero (-273.15 C).\n"
       "  {\"type\": \"illumination\", \"range\": [-10, 800]}\n"
       "Fix: use physical values."},
      {"E0311", "parameter must be positive",
       "time_constant, speed, droplet_radius and reach must be > 0.\n"
       "  \"time_constant\": 0\n"
       "Fix: use a positive value, or leave it out for the default."},
      {"E0312", "cone angle out of range",
       "An airflow cone_angle is the cone's half-angle in radians and must lie in\n"
       "(0, pi/2).\n"
       "  \"cone_angle\": 20        <- degrees by mistake\n"
       "Fix: use radians (0.35 is about 20 degrees)."},
      {"E0313", "negative drive stiffness or damping",
       "A geometry effect's drive stiffness and damping must be >= 0.\n"
       "Fix: use 0 or a positive value, or leave them out for the defaults."},
      {"E0314", "cumulative delta missing",
       "A cumulative mapping adds \"delta\" per press; it has no default.\n"
       "  {\"type\": \"cumulative\", \"threshold\": 0.002}\n"
       "Fix: add \"delta\" (negative for a \"minus\" button)."},
      {"E0315", "cumulative delta is zero",
       "A cumulative mapping with delta 0 never changes its output.\n"
       "Fix: use a non-zero delta."},
      {"E0316", "linear gain is zero",
       "A linear mapping's gain must be finite and non-zero (negative is allowed).\n"
       "Fix: give the output change per unit of receptor motion, or leave it out\n"
       "to map the receptor range onto the effect range."},
      {"E0317", "continuous receptor needs an explicit threshold or gain",
       "A continuous joint has no range, so the defaults that come from the range do\n"
       "not exist: binary, step and cumulative mappings need \"threshold\", linear\n"
       "mappings need \"gain\".\n"
       "Fix: add the threshold (radians) or the gain (units per radian)."},
      {"E0318", "threshold outside the receptor range",
       "A threshold must lie inside the receptor joint's [lo, hi], otherwise the\n"
       "receptor never reaches it and the function never fires. (Any finite\n"
       "threshold is fine for a continuous receptor.)\n"
       "  receptor range [0, 0.004], \"threshold\": 0.01\n"
       "Fix: pick a value in the range, or leave it out for the default."},
      {"E0319", "negative hysteresis",
       "A step mapping's hysteresis is the width below the threshold where the\n"
       "output holds; it must be >= 0.\n"
       "Fix: use 0 or a positive value."},
      {"E0320", "geometry effect range outside the effector joint's range",
       "Both ends of a geometry effect's range are joint targets and must lie inside\n"
       "the effector joint's [lo, hi] (any value for a continuous joint).\n"
       "  joint range [0, 1.57], effect \"range\": [0, 2.0]\n"
       "Fix: keep the targets inside the limits, or leave the range out to use them."},
      {"E0321", "cumulative initial outside the effect range",
       "A cumulative mapping's initial state must lie between the effect's two ends\n"
       "(the state is always clamped there).\n"
       "Fix: start inside the range, or leave it out (it defaults to the off end)."},
      {"E0322", "zero direction",
       "A fluid emitter's or airflow outlet's direction is [0, 0, 0].\n"
       "Fix: give a direction, e.g. [0, 0, -1] for straight down."},
      {"E0330", "geometry effect on a continuous joint needs a range",
       "A geometry effect's range defaults to its effector joint's range; a\n"
       "continuous joint has none.\n"
       "  \"effect\": {\"type\": \"geometry\"}   on a continuous effector\n"
       "Fix: give \"range\": [off, on] in radians."},
      // ---------------------------------------------------------------- E09xx
      {"E0900", "cannot write output",
       "A backend could not write its output (permissions, a full disk, a path that\n"
       "is a file). Output is all-or-nothing, so nothing in the output folder was\n"
       "changed. The command exits with code 2.\n"
       "Fix: check the -o folder is writable and has space."},
      {"E0901", "MuJoCo rejected or failed on the compiled model",
       "efc play compiled the spec for MuJoCo but MuJoCo could not load or step it.\n"
       "This is a compiler defect if the spec checked cleanly.\n"
       "Fix: report it with the spec; try a smaller --dt meanwhile."},
      {"E0902", "offscreen rendering is unavailable",
       "--render needs an OSMesa context (libosmesa6), which could not be created.\n"
       "Fix: install libosmesa6 (scripts/setup does), or play without --render."},
      {"E0903", "bad profile CSV",
       "The csv:FILE profile must have a header 't,<part>[,<part>...]' and rows of\n"
       "finite numbers with strictly increasing times; the line is the bad one.\n"
       "  t,handle\n  0,0\n  0.5,abc      <- not a number\n"
       "Fix: correct the row."},
      {"E0910", "bad command-line argument",
       "An option's value cannot be used: an unknown target, a --duration or --dt\n"
       "out of bounds, an unknown profile, a file that is neither .json nor .efc, an\n"
       "output path that is a file. Nothing was read or written. Exit code 2.\n"
       "Fix: see `efc <command> --help`."},
      {"E0911", "two specs have the same name",
       "efc compile with several specs writes OUTDIR/<name>/<target>/; two specs whose\n"
       "objects share a name would overwrite each other, so nothing is written.\n"
       "Fix: rename one object (its \"name\"), or compile them into different folders."},
      {"E0912", "parity does not hold",
       "efc parity ran the MuJoCo harness and the compiled Bullet program over the same\n"
       "receptor trajectory and a function's s_E or measured effector position differ\n"
       "beyond the tolerance the table's header names.\n"
       "Fix: the table shows which function and by how much; report it with the spec."},
      {"E0913", "a generated program could not be built or run",
       "efc parity builds the Bullet target with cmake and runs it; the build or the\n"
       "run failed. The tail of its log is printed. Exit code 2.\n"
       "Fix: install what the log says is missing (scripts/setup installs Bullet)."},
      // ---------------------------------------------------------------- E10xx
      {"E1001", "not a sequence folder",
       "A sequence (shared/spec/sequence.md) is a folder holding meta.json and rgb/.\n"
       "The path does not exist, is a file, is an empty folder, or has no readable\n"
       "meta.json.\n"
       "  efc check-sequence recordings/kitchen     (an empty folder)\n"
       "Fix: pass the sequence folder itself (the one with meta.json in it)."},
      {"E1002", "meta.json is invalid",
       "meta.json parsed as JSON but breaks a rule of grammar/sequence-meta.schema.json:\n"
       "a wrong type, a missing required key (efc_sequence, fps, width, height,\n"
       "intrinsics, frames), a size or fps that is not positive, an unknown role in\n"
       "\"parts\", a function naming a part \"parts\" does not list, or an unknown key\n"
       "(keys of your own start with \"x-\"). The position and pointer name the value.\n"
       "  \"width\": \"640\"            <- must be an integer\n"
       "Fix: correct the value; JSON syntax errors are E0003 as for specs."},
      {"E1003", "frame file missing",
       "meta.json says \"frames\": N, so rgb/ (and depth/ and each masks/<name>/ when\n"
       "they exist) must hold 000000.png to the file of frame N-1. One is missing, or\n"
       "there is no rgb/ folder at all.\n"
       "  SEQ/rgb/000002.png: error[E1003]: rgb frame 2 is missing\n"
       "Fix: supply the frame, or lower \"frames\" if the recording is shorter."},
      {"E1004", "frame of the wrong size",
       "A frame's width and height differ from meta.json's; the intrinsics are for\n"
       "that size, so the frame cannot be used as it is.\n"
       "  SEQ/depth/000123.png: depth frame is 320x240, meta.json says 640x480\n"
       "Fix: resize the frame (depth: nearest neighbour, never interpolate), or\n"
       "correct width, height and the intrinsics in meta.json."},
      {"E1005", "frame unreadable or of the wrong kind",
       "A frame is not a PNG, is truncated or corrupt, or is of another pixel kind than\n"
       "its folder holds: rgb/ 8-bit RGB, depth/ 16-bit grey, masks/ 8-bit grey. Nothing\n"
       "is converted silently (an RGBA or palette image may hide a wrong export).\n"
       "  SEQ/masks/hand/000000.png: mask frame is 8-bit RGB, expected 8-bit grey\n"
       "Fix: re-export the frame in the expected kind (e.g. `convert in.png -colorspace\n"
       "Gray -depth 8 out.png` for a mask)."},
      {"E1006", "poses.txt or hands.txt line invalid",
       "A data line of poses.txt needs 8 numbers (t tx ty tz qx qy qz qw, TUM), one of\n"
       "hands.txt 4 (t x y z, or t nan nan nan when no hand is seen). The line has the\n"
       "wrong count, a token that is not a number, a NaN or infinity in a pose, only\n"
       "some of x y z nan, a quaternion whose length is not 1 (within 0.001), or a\n"
       "time that is not after the previous line's.\n"
       "  0.1 0 0 1 0 0 0 2          <- quaternion of length 2\n"
       "Fix: correct the line; '#' starts a comment line."},
      {"E1007", "count does not match \"frames\"",
       "meta.json says how many frames the sequence has; poses.txt, hands.txt and\n"
       "truth/*.csv need one line (row) per frame, and no frame folder may hold a\n"
       "numbered frame at or past that count.\n"
       "  SEQ/poses.txt:299:1: error[E1007]: has 299 pose lines, meta.json says 300 frames\n"
       "Fix: add or remove lines (frames), or correct \"frames\"."},
      {"E1008", "truth/ file invalid",
       "A ground-truth file is malformed: truth/spec.json is not a JSON object,\n"
       "truth/object_pose.json lacks \"object_to_world\" (16 numbers, row-major, last\n"
       "row 0 0 0 1), or truth/joints.csv / effects.csv lack the header \"t,...\", have\n"
       "a duplicate column, a row of the wrong width, a field that is not a finite\n"
       "number, or times not increasing.\n"
       "  t,handle\n  0,0.1\n  0.033,abc       <- not a number\n"
       "Fix: regenerate truth/ (efc synth writes it), or correct the file."},
      {"E1009", "unknown mask name",
       "A folder masks/<name>/ must be named after a part that meta.json's \"parts\"\n"
       "lists, or a role: receptor, effector, object, hand (any name is accepted when\n"
       "\"parts\" is not given). Names are letters, digits and '_'.\n"
       "  masks/handel/   with \"parts\": {\"handle\": \"receptor\"}\n"
       "Fix: rename the folder, or add the part to \"parts\"."},
      {"E1030", "track line invalid",
       "A line of a track file (efc articulate --track) must hold the numbers its\n"
       "--format names: xyz: x y z (or t x y z, as hands.txt); pose7: x y z qx qy qz\n"
       "qw (more columns are ignored); tum: t x y z qx qy qz qw. Numbers must be\n"
       "finite, quaternions non-zero; '#' lines are comments.\n"
       "  0.1 0.2 abc     -> 'abc' is not a number\n"
       "Fix: correct the line, or pick the --format the file is in."},
      {"E1031", "track too short",
       "Telling fixed, revolute and prismatic apart needs at least 3 samples (and\n"
       "in practice a good part of the motion).\n"
       "Fix: record more of the motion."},
      {"E1050", "efc infer needs depth",
       "efc infer works on 3D points: every frame needs a depth map (depth/NNNNNN.png,\n"
       "16-bit, metres = value x depth_scale). Recordings without depth (the EgoFun3D\n"
       "videos) need an external monocular depth model's maps written there.\n"
       "Fix: put one depth PNG per frame in SEQ/depth/."},
      {"E1051", "efc infer needs camera poses",
       "Parts are registered in one world frame, so every frame needs its camera-to-\n"
       "world pose (poses.txt, TUM lines), e.g. from SLAM or visual odometry.\n"
       "Fix: write SEQ/poses.txt, one line per frame."},
      {"E1052", "a part has no masks",
       "meta.json lists a part, but masks/<part>/ does not exist, so efc infer\n"
       "cannot tell its pixels; the part is left out of the inferred object.\n"
       "Fix: supply an external segmenter's masks in masks/<part>/."},
      {"E1053", "no part masks at all",
       "efc infer needs to know which pixels belong to which part: masks/<part>/ for\n"
       "the parts of meta.json (or masks/receptor, masks/effector, masks/object).\n"
       "Without any, it falls back to what moves in the depth once the camera's own\n"
       "motion is taken out (a warning): one part 'moving' on a body 'body', with no\n"
       "names and the hand not told apart. When nothing moves either, it is an error.\n"
       "Fix: run a video segmenter and write its masks there."},
      {"E1054", "the inferred spec does not check",
       "efc infer checks the spec it built with the compiler before writing it; this\n"
       "error means a defect of efc infer on this recording. Nothing was written.\n"
       "Fix: report it with the sequence; the notes show what the compiler said."},
      {"E1055", "a function is left out of the inferred spec",
       "A function needs a receptor that moves and was reconstructed. When the\n"
       "recording never shows the receptor moving, efc infer does not invent a joint\n"
       "for it: the part is fixed and the function is left out. So is one whose\n"
       "effector was never reconstructed where its effect is the effector's own motion\n"
       "(geometry); other effects keep a stand-in (E1066).\n"
       "Fix: record the receptor being operated, and the effector, in view of the camera."},
      {"E1056", "no static part named",
       "efc infer registers the camera on the parts with the role 'object' (the body).\n"
       "Without one, the part seen most is taken as the static body.\n"
       "Fix: give the body the role \"object\" in meta.json's \"parts\"."},
      {"E1057", "the static body is not seen well enough",
       "The camera poses are corrected by registering each frame on the static parts;\n"
       "that needs their masks and depth readings in many frames.\n"
       "Fix: check the 'object' masks and the depth maps."},
      {"E1058", "a part could not be reconstructed",
       "A part needs depth readings inside its mask in several frames to get a\n"
       "surface and a closed mesh; this one did not, so it is left out.\n"
       "Fix: check the part's masks and depth, or film it from closer."},
      {"E1059", "a held part's motion is not seen: its joint is assumed",
       "efc infer types each part's joint by what its own track and the hand's contacts\n"
       "show. The hand held this part (a receptor), yet neither shows it moving: a button\n"
       "pressed under the finger, a knob turned by its centre. The recording is of\n"
       "someone operating it, so it takes a moving joint with low confidence\n"
       "(report.json: assumed_moving): the one its name names where it names one (a\n"
       "button, a key, a slider slides; a knob, a dial, a lever, a rocker turns;\n"
       "report.json: type_from_name), else the likelier of revolute and prismatic by\n"
       "BIC. A part no hand held stays fixed when nothing shows it moving. In a\n"
       "recording without the hand (no hands.txt), a receptor's role says someone\n"
       "operates it: it moves by the same assumption, its geometry from its own track.\n"
       "Fix: film the part from where its motion shows, not hidden by the hand."},
      {"E1066", "a function's effector was never seen: a sphere stands in for it",
       "The effector could not be reconstructed (E1058: no depth readings inside its\n"
       "mask), but its function's template was read (from the names where nothing\n"
       "responded, E1062). Rather than leave the function out, the spec gives the\n"
       "effector a stand-in: a sphere of 1 cm radius in the middle of the body's\n"
       "bounding box, fixed to the body. Its place and shape are guesses.\n"
       "Fix: film the effector, or move its stand-in in the spec by hand."},
      {"E1010", "the spec cannot be filmed by efc synth",
       "efc synth writes one mask folder per part and one for the hand (masks/hand/),\n"
       "so a part named 'hand' would share the hand's folder.\n"
       "  {\"name\": \"hand\", ...}   in \"parts\"\n"
       "Fix: rename the part (e.g. 'hand_wheel')."},
      {"E1020", "\"x-efc-object-to-world\" is malformed",
       "The extension places the spec's object frame in the world (efc eval compares\n"
       "specs there). It must be 16 finite numbers, a 4x4 matrix row-major, whose last\n"
       "row is 0 0 0 1 and whose 3x3 part is invertible.\n"
       "  \"x-efc-object-to-world\": [1, 0, 0, 0.5,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]\n"
       "Fix: write the matrix in full, or leave the key out (the identity)."},
      {"E1021", "bad line in an efc eval list of pairs",
       "Each line of the --list file is 'PRED GT' or 'PRED GT PRED_MASKS GT_SEQ',\n"
       "whitespace-separated, paths relative to the list file's folder; '#' starts a\n"
       "comment. GT must exist (a missing PRED is scored as a failure), GT_SEQ must be\n"
       "a folder, and the list must hold at least one pair.\n"
       "  pred/lamp.json  truth/lamp.json\n"
       "Fix: correct the line the error points at."},
      {"E1022", "cannot read the list of pairs",
       "efc eval --list could not open the file (it does not exist, is a folder, or is\n"
       "not readable).\n"
       "Fix: check the path."},
      // -------------------------------------------- function templates (warnings)
      {"E1060", "a function's receptor does not move",
       "efc infer reads a function's mapping from how its effect follows the receptor's\n"
       "joint position. The receptor is not among the parts, has no movable joint, or\n"
       "never moved in the recording, so the template is a guess with low confidence.\n"
       "Fix: record the receptor being operated through its range."},
      {"E1061", "a function's effector is never seen",
       "No frame shows pixels of the effector's mask (masks/<effector>/), so its glow\n"
       "and colour cannot be measured; the effect is judged from its joint and its\n"
       "surroundings only.\n"
       "Fix: keep the effector in view, or supply its masks."},
      {"E1062", "no signal follows the receptor",
       "None of the effector's signals (its joint, brightness, redness, droplets below\n"
       "it, air motes around it) is explained by the receptor better than by noise (BIC\n"
       "gain under 10). The effect is guessed, with low confidence, from the names of\n"
       "the effector and the function where they name one (\"spout\": fluid, \"hob_lamp\":\n"
       "illumination), else as temperature (a slow heater may not glow within the clip).\n"
       "The mapping is guessed from the receptor's name where it names one (a door,\n"
       "lid or drawer, a switch: binary; a slider, wheel or dimmer: linear; a plus,\n"
       "minus, up or down button: cumulative) with the spec's default parameters,\n"
       "else it is the best fit to the noise.\n"
       "Fix: a longer recording, the effector in view while it responds."},
      {"E1063", "the vision-language model gave no usable answer",
       "The optional adapter (--vlm-endpoint) could not reach the server, got an HTTP\n"
       "error, or a reply without the JSON asked for ({\"effect\", \"mapping\"}). The\n"
       "data-driven answer stands.\n"
       "Fix: check the endpoint, the model name and EFC_VLM_API_KEY."},
      {"E1064", "the vision-language adapter is unavailable",
       "The adapter loads libcurl at run time (libcurl.so.4) and needs <curl/curl.h> at\n"
       "build time; one of them is missing, so the endpoint is ignored.\n"
       "Fix: install libcurl4 (and libcurl4-openssl-dev to build), or leave it unset."},
      {"E1065", "frames unreadable for the function templates",
       "Some rgb frames could not be read; the function templates use the others.\n"
       "Fix: efc check-sequence SEQ names each bad file."},
      {"E1023", "predicted mask unreadable or of the wrong size",
       "A predicted mask DIR/masks/<part>/NNNNNN.png must be an 8-bit grey PNG of the\n"
       "true sequence's frame size (a missing frame counts as an empty mask).\n"
       "Fix: write the masks at the sequence's width and height, 8-bit grey."},
      {"E1040", "EgoFun3D dataset_metadata.json missing or invalid",
       "efc import-egofun3d DATASET reads DATASET/dataset_metadata.json: a list with one\n"
       "entry per video holding video_name, function_instance_id, cropped_video_path (or\n"
       "original_video_path), camera_extrinsics_path, camera_intrinsics_path,\n"
       "video_mask_path, geometry_type, geometry_path, part_annotation_path,\n"
       "articulation_path and function_annotation_path (paths relative to DATASET).\n"
       "The file is missing (exit 2), not a list, or an entry lacks a key or has one of\n"
       "the wrong type; or two video names give the same sequence folder. A bad entry\n"
       "fails its video only.\n"
       "  {\"video_name\": \"kitchen_01\", \"camera_extrinsics_path\": 3, ...}   <- not a string\n"
       "Fix: correct the entry the position points at."},
      {"E1041", "EgoFun3D video cannot be decoded",
       "The video an entry names does not exist, is not a file FFmpeg opens, has no video\n"
       "stream (or none the installed decoders read), or fails to decode part-way.\n"
       "Fix: check the path (relative to DATASET) and that `ffprobe FILE` reads it."},
      {"E1042", "EgoFun3D camera extrinsics invalid",
       "camera_extrinsics_path must be a NumPy .npy file (version 1.0-3.0, dtype '<f8' or\n"
       "'<f4', fortran_order False) of shape (N, 4, 4): one camera-to-world matrix per\n"
       "frame of the video, each a rigid transform. The header, the shape, the count N\n"
       "against the video's frames, or a matrix is wrong.\n"
       "  shape (120, 3, 4)   <- not (N, 4, 4)\n"
       "Fix: numpy.save(path, extrinsics.astype('<f8')) with one 4x4 matrix per frame."},
      {"E1043", "EgoFun3D camera intrinsics invalid",
       "camera_intrinsics_path holds undistorted_intrinsics (3x3) and original_frame_size\n"
       "[W, H]; a cropped video also needs cropped_intrinsics, cropped_top_left and\n"
       "cropped_bottom_right ([x, y], the bottom-right corner exclusive). A key is missing,\n"
       "a matrix is not [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], the crop box leaves the\n"
       "frame, or the video's frames are not the size these describe.\n"
       "Fix: correct the file, or point the entry at the video it belongs to."},
      {"E1044", "EgoFun3D mask file invalid",
       "video_mask_path is an HDF5 file with one group per part: an integer attribute\n"
       "mask_idx (3 receptor, 4 effector, 5 object) and a dataset masks of shape (T, H, W).\n"
       "The file is missing or not HDF5, a group lacks mask_idx or masks, T differs from\n"
       "the video's frame count, or H x W is neither the original frame nor the video's.\n"
       "  /knob/masks: masks has 118 frames (T), the video has 120\n"
       "Fix: write one mask per frame, at the original frame size (cropped on import)."},
      {"E1045", "EgoFun3D geometry PLY invalid",
       "geometry_path must be a PLY file, ascii or binary_little_endian, with a vertex\n"
       "element holding x, y and z and optionally a face element with vertex_indices. The\n"
       "header or the data is malformed, or a face names a vertex that does not exist.\n"
       "Fix: re-export the geometry (e.g. with Open3D's write_triangle_mesh)."},
      {"E1046", "EgoFun3D annotation invalid",
       "The part annotation must hold the video's function_instance_id with receptor and\n"
       "effector, each {label, indices, pid} (indices into the PLY's vertices); the\n"
       "articulation file a list of {pid, type, axis, origin, rangeMin, rangeMax} (type\n"
       "revolute, prismatic, continuous or fixed; rangeMin < rangeMax); the function\n"
       "annotation {function_instance_id, physics, func} with physics in geometry,\n"
       "illumination, temperature, fluid and func in binary, step, linear, cumulative.\n"
       "  \"physics\": \"heat\"   <- unknown\n"
       "Fix: correct the value the position points at."},
      {"E1047", "EgoFun3D annotations make no valid spec",
       "The importer builds truth/spec.json from the geometry and annotations of a video\n"
       "and checks it as efc check would; it failed (the message names the compiler's\n"
       "code, e.g. E0305 for a receptor without a movable joint: the articulation file\n"
       "has no entry for the receptor's pid, or a fixed one).\n"
       "Fix: complete the articulation annotation; `efc explain` the named code."},
      {"E1048", "EgoFun3D import cannot write its output",
       "The output folder, a frame or a truth file could not be written (exit 2), or the\n"
       "written sequence failed the sequence checks (a defect: please report it).\n"
       "Nothing is left behind for that video.\n"
       "Fix: check the output folder's permissions and free space."},
      {"E1049", "the EgoFun3D importer program is missing",
       "efc import-egofun3d runs the program efc-import-egofun3d, built next to efc, so\n"
       "that the efc program itself does not load FFmpeg and HDF5. It was not built\n"
       "(FFmpeg or HDF5 missing at configure time, or only the efc target was built).\n"
       "Fix: scripts/setup, then cmake --build build --target efc-import-egofun3d."},
      // ---------------------------------------------------------------- E11xx
      {"E1100", "bad line in an efc batch manifest",
       "Each line of the manifest is one job: PATH [ARG...], words separated by blanks.\n"
       "'...' quotes literally, \"...\" quotes with \\\" and \\\\ escapes, a backslash outside\n"
       "quotes escapes the next character, '#' starts a comment. A quote must be closed\n"
       "on its line. For commands that write a folder (compile, synth, infer, ...) a line\n"
       "may not give -o/--output: efc batch gives every job its own DIR/jobs/<id>/.\n"
       "  lamp.json --target \"all        <- the quote is not closed\n"
       "Nothing runs until every line is right.\n"
       "Fix: correct the line the error points at."},
      {"E1101", "cannot read the manifest",
       "efc batch could not open the manifest (it does not exist, is a folder, or is\n"
       "not readable). The command exits with code 2.\n"
       "Fix: check the path."},
      {"E1102", "the manifest holds no jobs",
       "Every line of the manifest is blank or a comment.\n"
       "Fix: write one spec or sequence path per line."},
      {"E1103", "no command, or one efc batch cannot run",
       "The jobs' command follows '--': efc batch MANIFEST -o DIR -- compile --target all.\n"
       "It must start with an efc command (not batch itself), and a command that\n"
       "writes a folder may not be given -o: batch sets each job's output folder.\n"
       "Fix: write '--' and the command after the batch's own options."},
      {"E1104", "bad shard",
       "--shard I/N takes the jobs I, I+N, I+2N, ... of the manifest; I and N are whole\n"
       "numbers with 0 <= I < N. Without --shard, SLURM_ARRAY_TASK_ID (minus\n"
       "SLURM_ARRAY_TASK_MIN) and SLURM_ARRAY_TASK_COUNT are used when both are set.\n"
       "  --shard 4/4      <- I runs from 0 to 3\n"
       "Fix: give a shard in range, or unset the Slurm variables."},
      {"E1105", "cannot write the batch folder",
       "efc batch could not create DIR, a job's folder, a record or a results file\n"
       "(permissions, a full disk), or could not start a job. Results already\n"
       "recorded are kept; the command exits with code 2.\n"
       "Fix: check the folder's permissions and free space, then run the same command again."},
      {"E1106", "the folder is not this batch's",
       "-o DIR must be a new or empty folder, or one that efc batch wrote for the same\n"
       "command (DIR/batch.json says which): a batch never writes into a folder of\n"
       "other files, and one folder holds the results of one command.\n"
       "Fix: choose another -o folder (or remove the old batch)."},
      {"E1110", "a job of the batch failed",
       "The job on this manifest line exited with a non-zero code (or was killed by a\n"
       "signal); the message shows its first error, DIR/logs/<id>.stderr all of it, and\n"
       "DIR/results.jsonl its record. The other jobs ran regardless; efc batch exits 1.\n"
       "Fix: correct the job's input; then efc batch ... --retry-failed runs the failed\n"
       "jobs again (and only them)."},
      {"E1111", "the batch was interrupted",
       "efc batch got SIGINT, SIGTERM or SIGHUP (Ctrl-C, kill, a Slurm time limit or\n"
       "pre-emption), passed it on to the running jobs and stopped. Jobs that had ended\n"
       "keep their results; the interrupted ones have none. The command exits with 2.\n"
       "Fix: run the same command again: it skips every job that has a result."},
      {"E1112", "a shard's results are missing",
       "efc batch --merge DIR needs DIR/results-I-of-N.jsonl for every I from 0 to N-1;\n"
       "one is not there (its array task did not run, failed to start, or was killed\n"
       "before it began). Nothing is merged: a missing shard is not guessed.\n"
       "Fix: run that shard again (the error shows the command), then merge again."},
      {"E1113", "a job has no result in its shard",
       "The shard's results file holds no record of this job (the task ran out of time,\n"
       "or was killed, before the job ended; or the manifest changed after the run).\n"
       "Nothing is merged.\n"
       "Fix: run the job's shard again: it skips the jobs that have results."},
      {"E1114", "shard results do not fit together",
       "The results files in DIR are of different shard counts N (an old split was left\n"
       "behind), or a line of one is not a complete job record.\n"
       "Fix: remove the old split's results-I-of-N.jsonl files, or run the broken shard\n"
       "again (its results are rebuilt from DIR/records/)."},
      {"E1115", "not a batch folder",
       "efc batch --merge DIR needs the folder the shards wrote into, with its\n"
       "batch.json (the list of jobs, written by --slurm and by every shard).\n"
       "Fix: give the -o folder of the batch."},
      {"E1116", "the Slurm job could not be submitted",
       "efc batch --slurm --submit runs sbatch --parsable on the script it wrote; sbatch\n"
       "is not installed or not in PATH, or it refused the job (its message follows).\n"
       "The script is kept (DIR/batch.sbatch).\n"
       "Fix: submit it yourself (sbatch DIR/batch.sbatch), or correct what sbatch said."},
      {"E1117", "a value cannot go into the Slurm script",
       "sbatch reads #SBATCH lines itself, not through a shell, and expands '%' in file\n"
       "names, so the values it reads there (the batch folder, for the log files;\n"
       "--mem, --time, --partition, --job-name) may hold only letters, digits, blanks\n"
       "and _ . / + , : = @ ~ -. Everything else in the script is quoted for the shell.\n"
       "Fix: choose a batch folder (or a value) without other characters."},
      {"E1118", "bad record in a batch results file",
       "efc eval --list DIR/results.jsonl reads the records efc batch wrote: one JSON\n"
       "object a line with job, path, exit_code and output. For an infer batch over\n"
       "sequences, each job's truth is PATH/truth/spec.json and its prediction\n"
       "DIR/OUTPUT/spec.json; a failed job is scored as a failed prediction. This line is\n"
       "not a record, or its sequence has no truth/spec.json.\n"
       "Fix: merge again (efc batch --merge DIR), or evaluate only sequences with truth."},
      // ---------------------------------------------------------------- warnings
      {"W0103", "mesh is not closed",
       "The mesh has holes or edges not shared by exactly two triangles, so its\n"
       "volume integrals are meaningless; mass and inertia come from its convex hull.\n"
       "Fix: close the mesh (or give \"mass\"; inertia still uses the hull)."},
      {"W0201", "joint axis is not a unit vector",
       "A joint axis is normalised by the compiler; a length far from 1 (by more than\n"
       "0.001) often signals a typo.\n"
       "  \"axis\": [0, 2, 0]\n"
       "Fix: write the unit vector ([0, 1, 0])."},
      {"W0202", "origin on a prismatic joint is ignored",
       "A slide has no pivot, so a prismatic joint's origin has no effect.\n"
       "Fix: remove the origin."},
      {"W0210", "initial position clamped into the joint range",
       "A joint's initial position lies outside its range; the initial state is\n"
       "clamped to the nearer limit.\n"
       "Fix: give an initial value inside the range."},
      {"W0901", "MuJoCo warned during playback",
       "MuJoCo reported a warning while stepping (e.g. too many contacts for the\n"
       "preallocated pool); results after it may be degraded.\n"
       "Fix: report it with the spec; a smaller --dt may help."},
      {"W0902", "profile CSV lacks a receptor",
       "A csv:FILE profile has no column for a receptor that the profile drives;\n"
       "that receptor holds its initial position.\n"
       "Fix: add a column named after the receptor part."},
      {"W0903", "hold value outside a receptor's range",
       "hold:V asks for a position outside a receptor's joint range; the joint limit\n"
       "stops it there.\n"
       "Fix: hold inside the range, or use hold:lo / hold:hi."},
      {"W0910", "efc convert cannot carry something over",
       "JSON has no comments, so converting a commented .efc file to JSON drops them;\n"
       "and mesh paths stay relative to the input's folder, so writing the output into\n"
       "another folder breaks them.\n"
       "Fix: keep the .efc file as the source, or move the meshes (or fix the paths)."},
      {"W0900", "backend cannot express a feature",
       "A target cannot express something in the spec (e.g. a spring, a light or a\n"
       "particle emitter); the warning names the feature and what was emitted\n"
       "instead. Nothing is dropped silently.\n"
       "Fix: none needed if the substitute is acceptable; otherwise use a target\n"
       "that supports the feature."},
  };
  return codes;
}

// Case-insensitive: `efc explain e0203` works too.
const CodeInfo* find_code(const std::string& code_in) {
  std::string code = code_in;
  for (auto& ch : code) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  const auto& codes = all_codes();
  auto it = std::find_if(codes.begin(), codes.end(),
                         [&](const CodeInfo& c) { return code == c.code; });
  return it == codes.end() ? nullptr : &*it;
}

}  // namespace efc
