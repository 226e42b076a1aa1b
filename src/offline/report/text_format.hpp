// Text helpers for reports: HTML escaping and number formatting for tables and axes.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace tpf::offline {

/// Escapes &, <, >, " and ' for use in HTML/SVG text and attribute values.
std::string html_escape(std::string_view text);

/// `value` with `significant` significant digits, fixed notation for 1e-3 ≤ |v| < 1e6 (no
/// trailing zeros beyond what the digits need), scientific otherwise; "–" for NaN; "−" as minus.
/// Examples: 280.17 → "280.2" (4 digits), 0.000123 → "1.23e−4", 1234567 → "1.235e6".
std::string format_number(double value, int significant = 4);

/// `value` with exactly `decimals` decimals, "−" as minus, "–" for NaN.
std::string format_fixed(double value, int decimals);

/// Percent change 100·(after − before)/before as "−88.6 %" (one decimal, sign always shown);
/// "–" when undefined.
std::string format_percent_change(double before, double after);

/// `items` with `separator` between them: joined({"a", "b"}, " + ") → "a + b".
std::string joined(const std::vector<std::string>& items, std::string_view separator);

/// Characters of UTF-8 `text` (the bytes that start one): what a column or a label's width counts.
std::size_t utf8_characters(std::string_view text);

/// printf of up to three numbers into a sentence: format_sentence("removes %.1f %%", 12.34).
std::string format_sentence(const char* pattern, double a, double b = 0, double c = 0);

}  // namespace tpf::offline
