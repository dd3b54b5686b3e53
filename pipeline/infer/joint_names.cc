#include "pipeline/infer/joint_names.h"

#include <map>

#include "pipeline/templates/effect_names.h"

namespace efc::pipeline {
namespace {

// Words that name one joint each (0 a slide, 1 a turn, 2 a slide into
// the face the part sits on: a press, 3 a turn about that face's normal:
// a knob, a dial). "up" and "down" name a press as
// "plus" and "minus" do: the pair of buttons that raise and lower a
// setting ("flow_up", "volume_down"; mapping_names.h reads them as steps
// up and down too). Left out on
// purpose: "switch" (rocker, toggle or slide), "handle" (a lever's or a
// drawer's), "valve" and "tap" (turned or pulled).
const std::map<std::string, int>& lexicon() {
  static const std::map<std::string, int> words = [] {
    std::map<std::string, int> w;
    for (const char* s : {"button", "pushbutton", "key", "plunger", "piston", "plus", "minus", "up", "down"})
      w[s] = 2;  // pressed in
    for (const char* s : {"slider", "slide", "fader", "drawer", "tray"}) w[s] = 0;
    for (const char* s : {"crank", "wheel", "handwheel", "thumbwheel", "lever", "rocker", "toggle", "paddle", "pedal",
                          "door", "lid", "flap", "hatch"})
      w[s] = 1;
    for (const char* s : {"knob", "dial"}) w[s] = 3;  // turned about the face it stands out of
    return w;
  }();
  return words;
}

}  // namespace

std::string joint_named(const std::string& part) {
  switch (last_named_in(lexicon(), part)) {
    case 0:
    case 2: return "prismatic";
    case 1:
    case 3: return "revolute";
    default: return "";
  }
}

bool press_named(const std::string& part) { return last_named_in(lexicon(), part) == 2; }

bool face_turn_named(const std::string& part) { return last_named_in(lexicon(), part) == 3; }

}  // namespace efc::pipeline
