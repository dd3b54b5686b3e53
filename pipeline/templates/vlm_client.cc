#include "pipeline/templates/vlm_client.h"

#include <algorithm>
#include <cctype>

#ifdef EFC_HAVE_CURL_H
#include <curl/curl.h>
#include <dlfcn.h>
#endif

namespace efc::pipeline {
namespace {

const char* const kEffectNames[5] = {"geometry", "illumination", "temperature", "fluid", "airflow"};
const char* const kMappingNames[4] = {"binary", "step", "linear", "cumulative"};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

int index_of(const std::string& name, const char* const* names, int n) {
  for (int i = 0; i < n; ++i)
    if (lower(name) == names[i]) return i;
  return -1;
}

void fold(const std::string& choice, const char* const* names, int n, std::vector<double>* p) {
  if (!p || static_cast<int>(p->size()) != n) return;
  const int c = index_of(choice, names, n);
  if (c < 0) return;
  double total = 0;
  for (int i = 0; i < n; ++i) {
    (*p)[i] *= i == c ? kVlmWeight : (1 - kVlmWeight) / (n - 1);
    total += (*p)[i];
  }
  if (total > 0)
    for (double& v : *p) v /= total;
}

#ifdef EFC_HAVE_CURL_H
// The few libcurl entry points, resolved once.
struct Curl {
  void* lib = nullptr;
  CURL* (*easy_init)() = nullptr;
  CURLcode (*easy_setopt)(CURL*, CURLoption, ...) = nullptr;
  CURLcode (*easy_perform)(CURL*) = nullptr;
  CURLcode (*easy_getinfo)(CURL*, CURLINFO, ...) = nullptr;
  void (*easy_cleanup)(CURL*) = nullptr;
  const char* (*easy_strerror)(CURLcode) = nullptr;
  curl_slist* (*slist_append)(curl_slist*, const char*) = nullptr;
  void (*slist_free_all)(curl_slist*) = nullptr;
  std::string error;
};

const Curl& curl() {
  static const Curl c = [] {
    Curl k;
    k.lib = dlopen("libcurl.so.4", RTLD_NOW | RTLD_LOCAL);
    if (!k.lib) {
      k.error = "libcurl.so.4 cannot be loaded";
      return k;
    }
    auto sym = [&](const char* name) { return dlsym(k.lib, name); };
    k.easy_init = reinterpret_cast<CURL* (*)()>(sym("curl_easy_init"));
    k.easy_setopt = reinterpret_cast<CURLcode (*)(CURL*, CURLoption, ...)>(sym("curl_easy_setopt"));
    k.easy_perform = reinterpret_cast<CURLcode (*)(CURL*)>(sym("curl_easy_perform"));
    k.easy_getinfo = reinterpret_cast<CURLcode (*)(CURL*, CURLINFO, ...)>(sym("curl_easy_getinfo"));
    k.easy_cleanup = reinterpret_cast<void (*)(CURL*)>(sym("curl_easy_cleanup"));
    k.easy_strerror = reinterpret_cast<const char* (*)(CURLcode)>(sym("curl_easy_strerror"));
    k.slist_append = reinterpret_cast<curl_slist* (*)(curl_slist*, const char*)>(sym("curl_slist_append"));
    k.slist_free_all = reinterpret_cast<void (*)(curl_slist*)>(sym("curl_slist_free_all"));
    if (!k.easy_init || !k.easy_setopt || !k.easy_perform || !k.easy_getinfo || !k.easy_cleanup || !k.easy_strerror ||
        !k.slist_append || !k.slist_free_all)
      k.error = "libcurl.so.4 lacks a curl_easy_* function";
    return k;
  }();
  return c;
}

size_t collect(char* data, size_t size, size_t n, void* user) {
  static_cast<std::string*>(user)->append(data, size * n);
  return size * n;
}
#endif

}  // namespace

std::string base64_encode(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += k[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += k[v >> 18], out += k[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string vlm_prompt(const std::string& function, const std::string& receptor, const std::string& effector) {
  return "These frames come from an egocentric video of a person operating an object (function '" + function +
         "'). The part tinted GREEN is the receptor ('" + receptor +
         "'): the part the person actuates. The part tinted MAGENTA is the effector ('" + effector +
         "'): the part that responds. The frames are in time order, before and after the actuation.\n"
         "Which physical effect does actuating the receptor have on the effector? Exactly one of:\n"
         "  geometry (the effector moves: a lid opens, a tray slides), illumination (it emits light),\n"
         "  temperature (it heats or cools), fluid (liquid flows out of it), airflow (air blows out of it).\n"
         "How does the receptor's state map to the effect? Exactly one of:\n"
         "  binary (on while actuated past a threshold, or toggled by each press),\n"
         "  step (switches on past a threshold, off again only below it by a margin),\n"
         "  linear (the effect follows the receptor's position proportionally),\n"
         "  cumulative (each press adds a fixed amount, which then holds).\n"
         "Answer with JSON only, no other text: {\"effect\": \"...\", \"mapping\": \"...\", \"reasons\": \"...\"}";
}

nlohmann::json vlm_request_body(const VlmRequest& req) {
  nlohmann::json content = nlohmann::json::array();
  content.push_back({{"type", "text"}, {"text", req.prompt}});
  for (const std::string& png : req.pngs)
    content.push_back({{"type", "image_url"}, {"image_url", {{"url", "data:image/png;base64," + base64_encode(png)}}}});
  return {{"model", req.model},
          {"temperature", 0},
          {"messages", nlohmann::json::array({{{"role", "user"}, {"content", content}}})}};
}

VlmAnswer parse_vlm_reply(const std::string& body) {
  VlmAnswer a;
  const nlohmann::json reply = nlohmann::json::parse(body, nullptr, false);
  if (reply.is_discarded() || !reply.is_object()) {
    a.error = "the reply is not JSON";
    return a;
  }
  const auto choices = reply.find("choices");
  if (choices == reply.end() || !choices->is_array() || choices->empty() || !(*choices)[0].is_object()) {
    a.error = "the reply has no choices";
    return a;
  }
  const nlohmann::json& msg = (*choices)[0].value("message", nlohmann::json::object());
  if (!msg.is_object() || !msg.contains("content") || !msg["content"].is_string()) {
    a.error = "the reply's message has no text content";
    return a;
  }
  const std::string text = msg["content"].get<std::string>();
  // The outermost {...}: tolerates code fences and words around it.
  const size_t open = text.find('{'), close = text.rfind('}');
  if (open == std::string::npos || close == std::string::npos || close < open) {
    a.error = "the answer holds no JSON object";
    return a;
  }
  const nlohmann::json ans = nlohmann::json::parse(text.substr(open, close - open + 1), nullptr, false);
  if (ans.is_discarded() || !ans.is_object()) {
    a.error = "the answer's JSON does not parse";
    return a;
  }
  const std::string effect = ans.contains("effect") && ans["effect"].is_string() ? lower(ans["effect"].get<std::string>()) : "";
  const std::string mapping =
      ans.contains("mapping") && ans["mapping"].is_string() ? lower(ans["mapping"].get<std::string>()) : "";
  if (index_of(effect, kEffectNames, 5) < 0 || index_of(mapping, kMappingNames, 4) < 0) {
    a.error = "the answer names no known effect and mapping ('" + effect + "', '" + mapping + "')";
    return a;
  }
  a.ok = true;
  a.effect = effect;
  a.mapping = mapping;
  if (ans.contains("reasons")) a.reasons = ans["reasons"].is_string() ? ans["reasons"].get<std::string>() : ans["reasons"].dump();
  return a;
}

bool vlm_available(std::string* why) {
#ifdef EFC_HAVE_CURL_H
  const Curl& c = curl();
  if (!c.error.empty()) {
    *why = c.error;
    return false;
  }
  return true;
#else
  *why = "efc was built without <curl/curl.h> (install libcurl4-openssl-dev and rebuild)";
  return false;
#endif
}

VlmAnswer ask_vlm(const VlmRequest& req) {
  VlmAnswer a;
#ifdef EFC_HAVE_CURL_H
  std::string why;
  if (!vlm_available(&why)) {
    a.error = why;
    return a;
  }
  const Curl& c = curl();
  CURL* h = c.easy_init();
  if (!h) {
    a.error = "curl_easy_init failed";
    return a;
  }
  std::string url = req.endpoint;
  while (!url.empty() && url.back() == '/') url.pop_back();
  url += "/chat/completions";
  const std::string body = vlm_request_body(req).dump();
  std::string reply;
  curl_slist* headers = c.slist_append(nullptr, "Content-Type: application/json");
  if (!req.api_key.empty()) headers = c.slist_append(headers, ("Authorization: Bearer " + req.api_key).c_str());
  const long timeout_ms = static_cast<long>(std::max(0.05, req.timeout_s) * 1000);
  c.easy_setopt(h, CURLOPT_URL, url.c_str());
  c.easy_setopt(h, CURLOPT_HTTPHEADER, headers);
  c.easy_setopt(h, CURLOPT_POSTFIELDS, body.c_str());
  c.easy_setopt(h, CURLOPT_POSTFIELDSIZE, static_cast<long>(body.size()));
  c.easy_setopt(h, CURLOPT_TIMEOUT_MS, timeout_ms);
  c.easy_setopt(h, CURLOPT_CONNECTTIMEOUT_MS, timeout_ms);
  c.easy_setopt(h, CURLOPT_NOSIGNAL, 1L);
  c.easy_setopt(h, CURLOPT_WRITEFUNCTION, &collect);
  c.easy_setopt(h, CURLOPT_WRITEDATA, &reply);
  const CURLcode rc = c.easy_perform(h);
  long status = 0;
  c.easy_getinfo(h, CURLINFO_RESPONSE_CODE, &status);
  c.easy_cleanup(h);
  c.slist_free_all(headers);
  if (rc != CURLE_OK) {
    a.error = std::string("request failed: ") + c.easy_strerror(rc);
    return a;
  }
  if (status < 200 || status >= 300) {
    a.error = "HTTP status " + std::to_string(status);
    return a;
  }
  return parse_vlm_reply(reply);
#else
  (void)req;
  vlm_available(&a.error);
  return a;
#endif
}

void combine_with_vlm(const VlmAnswer& answer, std::vector<double>* effects, std::vector<double>* mappings) {
  if (!answer.ok) return;
  fold(answer.effect, kEffectNames, 5, effects);
  fold(answer.mapping, kMappingNames, 4, mappings);
}

}  // namespace efc::pipeline
