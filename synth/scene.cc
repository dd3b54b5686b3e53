#include "synth/scene.h"

#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace efc::synth {
namespace {

using Eigen::Vector3d;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", std::fabs(v) < 1e-12 ? 0.0 : v);
  return buf;
}
std::string vec(const Vector3d& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }
std::string rgb(const std::array<double, 3>& c) { return num(c[0]) + " " + num(c[1]) + " " + num(c[2]); }
std::string rgba(const std::array<double, 3>& c, double a = 1) { return rgb(c) + " " + num(a); }

// A lamp's bulb or LED seen unlit: grey glass, its colour at kUnlitAlbedo
// (scene.h), so that lighting it (its material's emission, effect_visuals)
// shows. Without it a white bulb looks the same on and off, however bright
// the light. `attr` is the geom's rgba (MuJoCo's default where absent).
std::string unlit_rgba(const char* attr) {
  double c[4] = {0.5, 0.5, 0.5, 1};
  if (attr) std::sscanf(attr, "%lf %lf %lf %lf", &c[0], &c[1], &c[2], &c[3]);
  return rgba({c[0] * kUnlitAlbedo, c[1] * kUnlitAlbedo, c[2] * kUnlitAlbedo}, c[3]);
}

// Eight looks for the room: floor tiles, wall paint, counter, cabinet, clutter.
struct RoomStyle {
  std::array<double, 3> floor1, floor2, wall, counter, cabinet, clutter1, clutter2;
};
constexpr RoomStyle kStyles[8] = {
    {{0.55, 0.45, 0.35}, {0.45, 0.36, 0.28}, {0.86, 0.84, 0.78}, {0.30, 0.30, 0.32}, {0.75, 0.72, 0.66}, {0.8, 0.2, 0.15}, {0.2, 0.4, 0.7}},
    {{0.80, 0.80, 0.78}, {0.25, 0.25, 0.27}, {0.70, 0.78, 0.82}, {0.85, 0.83, 0.78}, {0.35, 0.42, 0.50}, {0.95, 0.75, 0.2}, {0.3, 0.6, 0.3}},
    {{0.62, 0.52, 0.40}, {0.58, 0.48, 0.37}, {0.93, 0.90, 0.82}, {0.55, 0.40, 0.28}, {0.90, 0.90, 0.88}, {0.1, 0.1, 0.12}, {0.85, 0.5, 0.6}},
    {{0.40, 0.42, 0.45}, {0.35, 0.37, 0.40}, {0.78, 0.70, 0.60}, {0.92, 0.92, 0.90}, {0.20, 0.25, 0.22}, {0.9, 0.9, 0.85}, {0.6, 0.15, 0.5}},
    {{0.72, 0.66, 0.55}, {0.30, 0.22, 0.16}, {0.60, 0.64, 0.58}, {0.18, 0.18, 0.20}, {0.82, 0.78, 0.70}, {0.25, 0.5, 0.85}, {0.9, 0.45, 0.1}},
    {{0.85, 0.85, 0.85}, {0.70, 0.70, 0.72}, {0.95, 0.93, 0.88}, {0.45, 0.32, 0.22}, {0.95, 0.95, 0.95}, {0.2, 0.2, 0.2}, {0.75, 0.1, 0.1}},
    {{0.50, 0.38, 0.30}, {0.42, 0.30, 0.24}, {0.82, 0.76, 0.86}, {0.65, 0.65, 0.68}, {0.40, 0.30, 0.25}, {0.95, 0.95, 0.3}, {0.15, 0.55, 0.55}},
    {{0.30, 0.32, 0.30}, {0.60, 0.62, 0.58}, {0.55, 0.58, 0.65}, {0.88, 0.86, 0.80}, {0.60, 0.52, 0.42}, {0.8, 0.3, 0.6}, {0.3, 0.3, 0.8}},
};

tinyxml2::XMLElement* child(tinyxml2::XMLElement* parent, const char* name) {
  tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  if (!e) e = parent->InsertNewChildElement(name);
  return e;
}

// A visual-only geom (no contacts; the model sets inertia explicitly, so no
// mass either): the dynamics stay efc play's.
tinyxml2::XMLElement* visual_geom(tinyxml2::XMLElement* parent, const std::string& name, const char* type,
                                  const std::string& size, const Vector3d& pos) {
  tinyxml2::XMLElement* g = parent->InsertNewChildElement("geom");
  g->SetAttribute("name", name.c_str());
  g->SetAttribute("type", type);
  g->SetAttribute("size", size.c_str());
  g->SetAttribute("pos", vec(pos).c_str());
  g->SetAttribute("contype", 0);
  g->SetAttribute("conaffinity", 0);
  return g;
}

tinyxml2::XMLElement* find_body(tinyxml2::XMLElement* parent, const std::string& name) {
  for (tinyxml2::XMLElement* e = parent->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (std::string(e->Name()) == "body") {
      const char* n = e->Attribute("name");
      if (n && name == n) return e;
      if (tinyxml2::XMLElement* found = find_body(e, name)) return found;
    }
  }
  return nullptr;
}

void add_textures(tinyxml2::XMLElement* asset, const RoomStyle& s) {
  auto texture = [&](const char* name, const char* builtin, const std::array<double, 3>& c1,
                     const std::array<double, 3>& c2, const char* mark, double random) {
    tinyxml2::XMLElement* t = asset->InsertNewChildElement("texture");
    t->SetAttribute("name", name);
    t->SetAttribute("type", "2d");
    t->SetAttribute("builtin", builtin);
    t->SetAttribute("width", 256);
    t->SetAttribute("height", 256);
    t->SetAttribute("rgb1", rgb(c1).c_str());
    t->SetAttribute("rgb2", rgb(c2).c_str());
    if (mark) {
      t->SetAttribute("mark", mark);
      t->SetAttribute("markrgb", rgb({c1[0] * 0.8, c1[1] * 0.8, c1[2] * 0.8}).c_str());
      t->SetAttribute("random", num(random).c_str());
    }
  };
  auto material = [&](const char* name, const char* tex, const char* repeat, double specular) {
    tinyxml2::XMLElement* m = asset->InsertNewChildElement("material");
    m->SetAttribute("name", name);
    m->SetAttribute("texture", tex);
    m->SetAttribute("texrepeat", repeat);
    m->SetAttribute("texuniform", "true");
    m->SetAttribute("specular", num(specular).c_str());
  };
  // Tiles and speckled paint: texture on the floor and walls, so neither
  // colour nor depth edges come only from the object.
  texture("efc_synth_floor_tex", "checker", s.floor1, s.floor2, "edge", 0);
  texture("efc_synth_wall_tex", "flat", s.wall, s.wall, "random", 0.04);
  material("efc_synth_floor", "efc_synth_floor_tex", "2 2", 0.1);
  material("efc_synth_wall", "efc_synth_wall_tex", "3 3", 0.05);
}

}  // namespace

Layout plan_layout(const Object& obj, const SceneKnobs& knobs) {
  Vector3d lo = Vector3d::Constant(1e300), hi = Vector3d::Constant(-1e300);
  for (const Part& p : obj.parts)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p.bbox_min[k]);
      hi[k] = std::max(hi[k], p.bbox_max[k]);
    }
  if (obj.parts.empty()) lo = hi = Vector3d::Zero();
  Layout L;
  L.lo = lo;
  L.hi = hi;
  L.center_object = 0.5 * (lo + hi);
  L.radius = std::max(0.03, 0.5 * (hi - lo).norm());
  const Vector3d span = hi - lo;
  // Kettles, faucets and lamps stand on a counter; fridges and stoves on the floor.
  L.on_counter = span.z() < 0.7 && std::max(span.x(), span.y()) < 0.9;
  L.support_z = L.on_counter ? 0.9 : 0.0;
  L.object_to_world = Eigen::Translation3d(knobs.object_x, knobs.object_y, L.support_z - lo.z()) *
                      Eigen::AngleAxisd(knobs.object_yaw, Vector3d::UnitZ());
  return L;
}

bool build_scene_mjcf(const Object& obj, const Layout& layout, const SceneKnobs& knobs,
                      const SceneExtras& extras, std::string* mjcf, std::string* error) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(mjcf->c_str(), mjcf->size()) != tinyxml2::XML_SUCCESS) {
    *error = std::string("cannot read the compiled model: ") + doc.ErrorStr();
    return false;
  }
  tinyxml2::XMLElement* root = doc.FirstChildElement("mujoco");
  tinyxml2::XMLElement* world = root ? root->FirstChildElement("worldbody") : nullptr;
  if (!world) {
    *error = "the compiled model has no <worldbody>";
    return false;
  }
  const RoomStyle& style = kStyles[((knobs.room_style % 8) + 8) % 8];

  // Rendering: the head camera's image size, no multisampling (segmentation
  // ids must not blend at edges), a modest shadow map for the software
  // renderer, and a dim headlight as the ambient fill.
  tinyxml2::XMLElement* visual = child(root, "visual");
  tinyxml2::XMLElement* global = child(visual, "global");
  global->SetAttribute("offwidth", extras.width);
  global->SetAttribute("offheight", extras.height);
  tinyxml2::XMLElement* quality = child(visual, "quality");
  quality->SetAttribute("shadowsize", 1024);
  quality->SetAttribute("offsamples", 0);
  // MuJoCo lights per vertex: box faces split into many quads let a lamp's
  // pool of light show on the counter and the wall.
  quality->SetAttribute("numquads", 4);
  // Fewer facets on round geoms (default 28 x 16): droplets and fingers are
  // small on screen, and the software renderer pays per triangle.
  quality->SetAttribute("numslices", 16);
  quality->SetAttribute("numstacks", 10);
  tinyxml2::XMLElement* headlight = child(visual, "headlight");
  const double a = std::clamp(knobs.ambient, 0.0, 1.0);
  headlight->SetAttribute("ambient", rgb({a, a, a}).c_str());
  headlight->SetAttribute("diffuse", rgb({0.25, 0.25, 0.25}).c_str());
  headlight->SetAttribute("specular", rgb({0.05, 0.05, 0.05}).c_str());

  tinyxml2::XMLElement* asset = root->FirstChildElement("asset");
  if (!asset) {
    asset = doc.NewElement("asset");
    root->InsertAfterChild(visual, asset);
  }
  add_textures(asset, style);
  for (const std::string& fn : extras.glow_functions) {
    tinyxml2::XMLElement* m = asset->InsertNewChildElement("material");
    m->SetAttribute("name", (kGlowMaterialPrefix + fn).c_str());
    m->SetAttribute("emission", 0);
  }

  // efc's own floor, camera and light frame a still object; the room replaces them.
  for (tinyxml2::XMLElement* e = world->FirstChildElement(); e;) {
    tinyxml2::XMLElement* next = e->NextSiblingElement();
    const char* n = e->Attribute("name");
    if (n && (std::string(n) == "efc_floor" || std::string(n) == "efc_camera" ||
              std::string(n) == "efc_scene_light"))
      world->DeleteChild(e);
    e = next;
  }
  // Illumination effectors glow: their geoms share a material whose emission
  // follows the light's output each frame.
  for (const std::string& fn : extras.glow_functions) {
    for (const Function& f : obj.functions) {
      if (f.name != fn) continue;
      if (tinyxml2::XMLElement* body = find_body(world, f.effector))
        for (tinyxml2::XMLElement* g = body->FirstChildElement("geom"); g; g = g->NextSiblingElement("geom")) {
          g->SetAttribute("material", (kGlowMaterialPrefix + fn).c_str());
          g->SetAttribute("rgba", unlit_rgba(g->Attribute("rgba")).c_str());
        }
    }
  }

  // The room, in the object's frame (the simulation's world): the room is
  // built square to the object, which faces -y.
  const Vector3d& lo = layout.lo;
  const Vector3d& hi = layout.hi;
  const Vector3d c = layout.center_object;
  const double floor_z = lo.z() - layout.support_z;
  const double wall_y = hi.y() + (layout.on_counter ? 0.10 : 0.30);
  const double half_w = std::max(2.2, 0.5 * (hi.x() - lo.x()) + 1.5);

  tinyxml2::XMLElement* floor = visual_geom(world, "efc_synth_room_floor", "plane", "6 6 0.05",
                                            Vector3d(c.x(), c.y(), floor_z));
  floor->SetAttribute("material", "efc_synth_floor");
  tinyxml2::XMLElement* wall = visual_geom(world, "efc_synth_room_wall", "box",
                                           num(half_w) + " 0.03 1.4", Vector3d(c.x(), wall_y + 0.03, floor_z + 1.4));
  wall->SetAttribute("material", "efc_synth_wall");
  for (int s : {-1, 1})
    visual_geom(world, s < 0 ? "efc_synth_room_left_wall" : "efc_synth_room_right_wall", "box", "0.03 2.5 1.4",
                Vector3d(c.x() + s * half_w, wall_y - 2.5, floor_z + 1.4))
        ->SetAttribute("material", "efc_synth_wall");

  // Clutter beside the object: a mug and a carton on its support, so the
  // object is not the only thing on it.
  const double support = lo.z();
  const double side_x = 0.5 * (hi.x() - lo.x()) + 0.12 + 0.04 * (knobs.room_style % 3);
  const double front_y = std::max(lo.y(), wall_y - 0.6);
  if (layout.on_counter) {
    const double depth = std::max(0.65, wall_y - lo.y() + 0.2);
    // The worktop is a plane (MuJoCo draws planes as a fine grid, so a lamp's
    // light pool shows on it) over a cabinet box.
    tinyxml2::XMLElement* top = visual_geom(world, "efc_synth_room_counter", "plane",
                                            num(half_w) + " " + num(0.5 * depth) + " 0.02",
                                            Vector3d(c.x(), wall_y - 0.5 * depth, support - 0.0005));
    // Untextured: MuJoCo's textured materials hide the per-vertex pool of a
    // lamp's light, and a lamp lighting the worktop is what illumination
    // effects should show.
    top->SetAttribute("rgba", rgba(style.counter).c_str());
    tinyxml2::XMLElement* cab = visual_geom(world, "efc_synth_room_cabinet", "box",
                                            num(half_w) + " " + num(0.5 * depth) + " " +
                                                num(0.5 * (support - 0.001 - floor_z)),
                                            Vector3d(c.x(), wall_y - 0.5 * depth,
                                                     floor_z + 0.5 * (support - 0.001 - floor_z)));
    cab->SetAttribute("rgba", rgba(style.cabinet).c_str());
  }
  visual_geom(world, "efc_synth_clutter_mug", "cylinder", "0.04 0.05",
              Vector3d(c.x() + side_x + 0.05, front_y + 0.12, support + 0.05))
      ->SetAttribute("rgba", rgba(style.clutter1).c_str());
  visual_geom(world, "efc_synth_clutter_carton", "box", "0.08 0.035 0.12",
              Vector3d(c.x() - side_x - 0.1, front_y + 0.2, support + 0.12))
      ->SetAttribute("rgba", rgba(style.clutter2).c_str());

  // Lights: a key light from above and to the side (it casts the shadows),
  // and a weak fill from the other side.
  const double la = knobs.light_azimuth, li = std::max(0.0, knobs.light_intensity);
  const Vector3d key_dir(std::sin(la) * 0.6, std::cos(la) * 0.3 + 0.2, -1.0);
  tinyxml2::XMLElement* key = world->InsertNewChildElement("light");
  key->SetAttribute("name", "efc_synth_key_light");
  key->SetAttribute("directional", "true");
  key->SetAttribute("castshadow", "true");
  key->SetAttribute("pos", vec(c + Vector3d(0, 0, 3)).c_str());
  key->SetAttribute("dir", vec(key_dir.normalized()).c_str());
  key->SetAttribute("diffuse", rgb({0.65 * li, 0.63 * li, 0.6 * li}).c_str());
  key->SetAttribute("specular", rgb({0.2, 0.2, 0.2}).c_str());
  tinyxml2::XMLElement* fill = world->InsertNewChildElement("light");
  fill->SetAttribute("name", "efc_synth_fill_light");
  fill->SetAttribute("directional", "true");
  fill->SetAttribute("castshadow", "false");
  fill->SetAttribute("pos", vec(c + Vector3d(0, -2, 2)).c_str());
  fill->SetAttribute("dir", vec(Vector3d(-key_dir.x(), 0.6, -0.7).normalized()).c_str());
  fill->SetAttribute("diffuse", rgb({0.18 * li, 0.18 * li, 0.2 * li}).c_str());
  fill->SetAttribute("specular", rgb({0, 0, 0}).c_str());

  // Mocap bodies start high above the object: the runtime measures the
  // object's lowest point at reset (droplets recycle below it) from every
  // geom that is not on the world body.
  const Vector3d parked = c + Vector3d(0, 0, layout.radius + 2.0);
  tinyxml2::XMLElement* head = world->InsertNewChildElement("body");
  head->SetAttribute("name", kHeadBody);
  head->SetAttribute("mocap", "true");
  head->SetAttribute("pos", vec(parked).c_str());
  tinyxml2::XMLElement* cam = head->InsertNewChildElement("camera");
  cam->SetAttribute("name", kCamera);
  cam->SetAttribute("fovy", num(extras.fovy_deg).c_str());

  if (!extras.hand_xml.empty()) {
    tinyxml2::XMLDocument hand;
    if (hand.Parse(extras.hand_xml.c_str()) != tinyxml2::XML_SUCCESS || !hand.FirstChildElement()) {
      *error = "internal: the hand model is not XML";
      return false;
    }
    tinyxml2::XMLNode* copy = hand.FirstChildElement()->DeepClone(&doc);
    world->InsertEndChild(copy);
  }
  for (const AirMotes& air : extras.air) {
    for (int i = 0; i < air.count; ++i) {
      tinyxml2::XMLElement* b = world->InsertNewChildElement("body");
      b->SetAttribute("name", (kAirPrefix + air.function + "_" + std::to_string(i)).c_str());
      b->SetAttribute("mocap", "true");
      b->SetAttribute("pos", vec(parked).c_str());
      // Light streaks along the flow (the body's z axis), like ribbons of dust.
      visual_geom(b, "", "capsule", "0.002 0.012", Vector3d::Zero())
          ->SetAttribute("rgba", "0.92 0.95 1 0.85");
      b->FirstChildElement("geom")->DeleteAttribute("name");
    }
  }

  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  *mjcf = printer.CStr();
  return true;
}

}  // namespace efc::synth
