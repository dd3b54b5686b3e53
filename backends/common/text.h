// Number formatting and escaping for every language a backend writes: XML
// (MJCF, URDF), C++ (callbacks, the Bullet program), Python (the Python
// targets) and JSON (through nlohmann). One function per job, so a spec's text
// reaches generated files through exactly one door per language.
#pragma once

#include <string>

#include "compiler/ir.h"

namespace efc {
namespace text {

// Shortest text that reads back as exactly `v` (std::to_chars): XML, C++,
// Python and JSON all parse it, so generated code gets bit-identical doubles.
// -0 prints as "0" (nicer, same value).
std::string number(double v);
// "x y z" with number() (XML attribute vectors).
std::string vec3(const Vec3& v);
// A C++ double literal that reads back exactly: number() with ".0" added when
// it would otherwise read as an integer ("3" -> "3.0").
std::string cpp_double(double v);

// Text for an XML attribute value or comment: & < > " ' escaped, "--" split
// (never closes a comment), control characters other than tab and newline
// (not XML 1.0 characters) turned into spaces.
std::string xml_escape(const std::string& s);
// Text for inside <!-- -->: only what a comment cannot hold is changed ("--"
// split, a trailing "-" padded, control characters as spaces).
std::string xml_comment(const std::string& s);

// A C++ string literal, quotes included: backslash, quote and every byte
// outside printable ASCII escaped (octal), so any text is one literal.
std::string cpp_string_literal(const std::string& s);

// Text for a C++ `//` comment: control characters (a newline would end the
// comment) turned into spaces, and a "." after a trailing backslash (which
// would continue the comment onto the next line).
std::string cpp_comment(const std::string& s);

// A Python string literal, quotes included ('...'): printable ASCII as is
// (backslash and quote escaped), every other byte or code point escaped
// (\n, \t, \xNN, \uNNNN, \UNNNNNNNN), so the literal is pure ASCII, one line,
// and evaluates to exactly `s` (invalid UTF-8 bytes become U+FFFD). Nothing
// in it can end the literal, start a new statement or look like another
// character (unicode look-alikes are escaped).
std::string python_string_literal(const std::string& s);

}  // namespace text
}  // namespace efc
