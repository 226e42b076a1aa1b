#include "offline/report/text_format.hpp"

#include <cmath>
#include <cstdio>

#include "offline/regimes/regime_stats.hpp"

namespace tpf::offline {
namespace {

constexpr std::string_view kMinus = "\u2212";
constexpr std::string_view kDash = "\u2013";

/// Replaces a leading '-' and an exponent's '-' by the typographic minus.
std::string typographic_minus(std::string text) {
  std::string out;
  for (const char c : text) {
    if (c == '-')
      out += kMinus;
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string format_number(double value, int significant) {
  if (std::isnan(value)) return std::string(kDash);
  if (std::isinf(value)) return value > 0 ? "\u221e" : std::string(kMinus) + "\u221e";
  if (value == 0.0) return "0";
  const double magnitude = std::abs(value);
  char buffer[64];
  if (magnitude >= 1e-3 && magnitude < 1e6) {
    const int integer_digits = static_cast<int>(std::floor(std::log10(magnitude))) + 1;
    const int decimals = std::max(0, significant - integer_digits);
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return typographic_minus(buffer);
  }
  std::snprintf(buffer, sizeof buffer, "%.*e", std::max(0, significant - 1), value);
  std::string text = buffer;  // e.g. 1.230e-04 → 1.23e−4
  const std::size_t e = text.find('e');
  std::string mantissa = text.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    while (mantissa.back() == '0')
      mantissa.pop_back();
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  const int exponent = std::stoi(text.substr(e + 1));
  return typographic_minus(mantissa + "e" + std::to_string(exponent));
}

std::string format_fixed(double value, int decimals) {
  if (std::isnan(value)) return std::string(kDash);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string text = buffer;
  if (text.find_first_not_of("-0.") == std::string::npos) text = text.substr(text[0] == '-');
  return typographic_minus(text);
}

std::string format_percent_change(double before, double after) {
  const double change = percent_change(before, after);
  if (std::isnan(change)) return std::string(kDash);
  std::string text = change >= 0.05 ? "+" : "";
  text.append(format_fixed(change, 1)).append("\u00a0%");
  return text;
}

std::string joined(const std::vector<std::string>& items, std::string_view separator) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text.append(i ? separator : "").append(items[i]);
  return text;
}

std::string format_sentence(const char* pattern, double a, double b, double c) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

std::size_t utf8_characters(std::string_view text) {
  std::size_t n = 0;
  for (const char c : text)
    n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

}  // namespace tpf::offline
