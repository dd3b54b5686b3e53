#include "pipeline/templates/effect_names.h"

#include <cctype>
#include <map>
#include <vector>

namespace efc::pipeline {
namespace {

// Words that name one effect each. Left out on purpose: words that name
// several ("head": a fan's, a shower's, a kettle's; "panel"; "speed";
// "pot"; "grill", a heater, beside "grille", a vent) and the parts that
// operate rather than respond ("knob", "button", "handle", "switch").
const std::map<std::string, int>& lexicon() {
  static const std::map<std::string, int> words = [] {
    std::map<std::string, int> w;
    for (const char* s : {"open", "close", "lid", "door", "drawer", "flap", "hatch", "cover", "tray", "extend",
                          "lift", "raise", "eject", "release", "pop", "shutter", "gate"})
      w[s] = 0;
    for (const char* s : {"light", "lamp", "bulb", "led", "indicator", "glow", "lantern", "backlight", "lighting",
                          "illumination", "beacon", "torch", "flashlight"})
      w[s] = 1;
    for (const char* s : {"heat", "heater", "heating", "burner", "hob", "stove", "cooktop", "hotplate", "element",
                          "boiler", "temperature", "warm", "warmer", "hot", "toast", "toaster", "oven", "radiator",
                          "thermostat", "cook"})
      w[s] = 2;
    for (const char* s : {"water", "fluid", "liquid", "flow", "spout", "nozzle", "faucet", "tap", "shower", "spray",
                          "sprayer", "sprinkler", "pour", "brew", "drip", "jet", "fountain", "dispense", "dispenser",
                          "rinse", "wash"})
      w[s] = 3;
    for (const char* s : {"air", "airflow", "fan", "blower", "blow", "vent", "ventilation", "grille", "extract",
                          "extractor", "exhaust", "wind", "breeze", "draft", "draught", "propeller", "ventilator"})
      w[s] = 4;
    return w;
  }();
  return words;
}

std::vector<std::string> name_words(const std::string& name) {
  std::vector<std::string> out;
  std::string cur;
  auto flush = [&] {
    if (!cur.empty()) out.push_back(cur), cur.clear();
  };
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (!std::isalnum(c)) {
      flush();
      continue;
    }
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(name[i - 1]))) flush();
    cur.push_back(static_cast<char>(std::tolower(c)));
  }
  flush();
  return out;
}

int word_value(const std::map<std::string, int>& words, const std::string& word) {
  auto it = words.find(word);
  if (it != words.end()) return it->second;
  if (word.size() > 3 && word.back() == 's') {
    it = words.find(word.substr(0, word.size() - 1));
    if (it != words.end()) return it->second;
  }
  return -1;
}

}  // namespace

int last_named_in(const std::map<std::string, int>& words, const std::string& name) {
  int found = -1;
  for (const std::string& word : name_words(name))
    if (const int v = word_value(words, word); v >= 0) found = v;
  return found;
}

int effect_named(const std::string& effector, const std::string& function) {
  const int e = last_named_in(lexicon(), effector);
  return e >= 0 ? e : last_named_in(lexicon(), function);
}

}  // namespace efc::pipeline
