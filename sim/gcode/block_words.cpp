#include "sim/gcode/block_words.h"

#include <cmath>
#include <string>

#include "sim/gcode/motion.h"

namespace mdhd::gcode {

void failAt(const Block& block, int column, const std::string& message) {
  SourcePos pos = block.pos;
  // An error of the whole block points at its first word (a block has at least one).
  pos.column = column > 0 ? column : block.words.empty() ? 1 : block.words.front().column;
  throw GcodeError(std::move(pos), message);
}

namespace {

// Code x10 of a G/M value, -1 when it is not a multiple of 0.1.
int code10(double v) {
  if (!(v >= 0.0) || v > 10000.0) return -1;
  double scaled = v * 10.0;
  double r = std::round(scaled);
  if (std::fabs(scaled - r) > 1e-6) return -1;
  return static_cast<int>(r);
}

int axisIndex(char c) {
  for (int i = 0; i < kAxisCount; ++i)
    if (kAxisLetters[i] == c) return i;
  return -1;
}

// Codes LinuxCNC 2.9 knows and mdhd does not run: refused with their name, so
// that a machinist does not look for a typing error.
const char* unsupportedCode(char letter, int c) {
  if (letter == 'G') {
    switch (c) {
      case 70:
      case 80:
        return "lathe diameter/radius mode";
      case 171:
      case 181:
      case 191:
        return "UVW plane selection";
      case 700:
      case 710:
      case 711:
      case 712:
      case 720:
      case 721:
      case 722:
        return "lathe roughing/finishing cycle";
      case 760:
        return "threading cycle";
      default:
        return nullptr;
    }
  }
  switch (c) {
    case 700:
    case 710:
    case 720:
    case 730:
      return "modal state save/restore";
    case 980:
    case 990:
      return "Fanuc-style subprogram call/return; use O-word sub/call";
    default:
      return nullptr;
  }
}

[[noreturn]] void failUnknown(const Block& block, const Word& w, int c) {
  const char letter = w.letter;
  if (const char* what = c < 0 ? nullptr : unsupportedCode(letter, c)) {
    std::string code = std::string(1, letter) + std::to_string(c / 10);
    if (c % 10 != 0) code += "." + std::to_string(c % 10);
    failAt(block, w.column, code + " (" + what + ") is not supported");
  }
  failAt(block, w.column, letter == 'G' ? "Unknown g code used" : "Unknown m code used");
}

void addG(const Block& block, const Word& w, BlockWords& out) {
  const int c = code10(w.value);
  const CodeInfo* info = c < 0 ? nullptr : findGCode(c);
  if (!info) failUnknown(block, w, c);
  int& slot = out.g[info->group];
  if (info->group == kGMotion && slot != -1 && (slot == 800 || c == 800)) {
    // LinuxCNC: G80 beside another motion code is ignored (in either order).
    if (c == 800) return;
  } else if (slot != -1) {
    failAt(block, w.column, "Two G codes used from same modal group");
  }
  slot = c;
  out.g_column[info->group] = w.column;
}

void addM(const Block& block, const Word& w, BlockWords& out) {
  const int c = code10(w.value);
  const CodeInfo* info = c < 0 ? nullptr : findMCode(c);
  if (!info) failUnknown(block, w, c);
  int& slot = out.m[info->group];
  if (slot != -1) {
    const bool pair =
        info->group == kMCoolant && ((slot == 70 && c == 80) || (slot == 80 && c == 70));
    if (!pair || out.mist_and_flood)
      failAt(block, w.column, "Two M codes used from same modal group");
    out.mist_and_flood = true;
    return;
  }
  slot = c;
  out.m_column[info->group] = w.column;
}

}  // namespace

void readBlockWords(const Block& block, unsigned axis_mask, BlockWords& out) {
  out.g.fill(-1);
  out.m.fill(-1);
  out.mist_and_flood = false;
  out.letters = 0;
  out.axis_column = 0;
  out.has_radius = out.has_angle = false;
  out.polar_column = 0;
  out.spindle_column = 0;
  for (const Word& w : block.words) {
    const char c = w.letter;
    if (c == '$') {  // spindle select: this machine has one spindle, $0 ($-1: all of them)
      if (out.spindle_column != 0)
        failAt(block, w.column, "Multiple spindle choice ($) words on one line");
      const double number = std::trunc(w.value);  // LinuxCNC drops the fraction
      if (number != 0.0 && number != -1.0)
        failAt(block, w.column, "Invalid spindle ($) number: the machine has one spindle, $0");
      out.spindle_column = w.column;
      continue;
    }
    if (c == '@' || c == '^') {
      (c == '@' ? out.has_radius : out.has_angle) = true;
      (c == '@' ? out.radius : out.angle) = w.value;
      if (out.polar_column == 0) out.polar_column = w.column;
      if (out.axis_column == 0) out.axis_column = w.column;
      continue;
    }
    if (c < 'A' || c > 'Z') failAt(block, w.column, std::string("Bad character '") + c + "' used");
    if (c == 'G') {
      addG(block, w, out);
      continue;
    }
    if (c == 'M') {
      addM(block, w, out);
      continue;
    }
    const int axis = axisIndex(c);
    if (axis >= 0) {
      if (!((axis_mask >> axis) & 1u)) {
        // LinuxCNC's words, then what the machinist needs: which axes there are.
        const char lower = static_cast<char>(c - 'A' + 'a');
        std::string axes;
        for (int i = 0; i < kAxisCount; ++i)
          if ((axis_mask >> i) & 1u) axes += std::string(axes.empty() ? "" : " ") + kAxisLetters[i];
        failAt(block, w.column,
               std::string("Bad character '") + lower + "' used: the machine has no " + c +
                   " axis (its axes: " + (axes.empty() ? "none" : axes) + ")");
      }
      if (out.axis_column == 0) out.axis_column = w.column;
    }
    const unsigned bit = 1u << (c - 'A');
    if (out.letters & bit)
      failAt(block, w.column, std::string("Multiple ") + c + " words on one line");
    out.letters |= bit;
    out.value[c - 'A'] = w.value;
    out.column[c - 'A'] = w.column;
  }
}

}  // namespace mdhd::gcode
