// SPDX-License-Identifier: BSD-3-Clause
#include "Core/TextLists.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace msynth
{

std::vector<std::string> SplitText(const std::string& text, char separator, bool dropSpaces)
{
  std::vector<std::string> parts(1);
  for (char c : text)
  {
    if (c == separator)
      parts.emplace_back();
    else if (!(dropSpaces && c == ' '))
      parts.back() += c;
  }
  return parts;
}

bool ParseInteger(const std::string& text, long long low, long long high, long long& value)
{
  const std::size_t first = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() == first || text.size() - first > 18)
    return false;
  long long v = 0;
  for (std::size_t i = first; i < text.size(); ++i)
  {
    if (text[i] < '0' || text[i] > '9')
      return false;
    v = v * 10 + (text[i] - '0');
  }
  v = first ? -v : v;
  if (v < low || v > high)
    return false;
  value = v;
  return true;
}

namespace
{
/// The "a:b" entries of @p text (separated by commas, semicolons or spaces), each split at its
/// one colon; false for an entry without exactly one colon.
template <typename Entry>
void ForEachEntry(
  const std::string& text, const std::string& what, const std::string& form, Entry&& entry)
{
  std::string item;
  auto flush = [&]()
  {
    if (item.empty())
      return;
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos || item.find(':', colon + 1) != std::string::npos ||
      !entry(item.substr(0, colon), item.substr(colon + 1)))
      throw Error(what + ": '" + item + "' is not " + form);
    item.clear();
  };
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    if (c == ' ' || c == '\t')
    {
      // Spaces around a colon belong to the entry ("1 : 2" is "1:2").
      std::size_t next = text.find_first_not_of(" \t", i);
      if ((!item.empty() && item.back() == ':') || (next != std::string::npos && text[next] == ':'))
        continue;
      flush();
    }
    else if (c == ',' || c == ';')
      flush();
    else
      item += c;
  }
  flush();
}

bool ParseLabel(const std::string& text, Label& label)
{
  long long v = 0;
  if (!ParseInteger(text, std::numeric_limits<Label>::min(), std::numeric_limits<Label>::max(), v))
    return false;
  label = static_cast<Label>(v);
  return true;
}
} // namespace

std::map<Label, Label> ParseLabelPairs(const std::string& text, bool both, const std::string& what)
{
  std::map<Label, Label> map;
  ForEachEntry(text, what, "a pair 'a:b' of labels",
    [&](const std::string& a, const std::string& b)
    {
      Label la = 0, lb = 0;
      if (!ParseLabel(a, la) || !ParseLabel(b, lb))
        return false;
      map[la] = lb;
      if (both)
        map[lb] = la;
      return true;
    });
  return map;
}

std::map<Label, double> ParseLabelValues(
  const std::string& text, const std::string& what, const std::string& value)
{
  std::map<Label, double> values;
  ForEachEntry(text, what, "'label:" + value + "'",
    [&](const std::string& a, const std::string& b)
    {
      Label label = 0;
      if (!ParseLabel(a, label) || b.empty())
        return false;
      char* end = nullptr;
      const double v = std::strtod(b.c_str(), &end);
      if (*end != '\0' || !std::isfinite(v))
        return false;
      values[label] = v;
      return true;
    });
  return values;
}

std::vector<CountEntry> ParseCountEntries(const std::string& text, const std::string& what)
{
  std::vector<CountEntry> entries;
  std::string list = text;
  std::replace(list.begin(), list.end(), ';', ',');
  for (std::string item : SplitText(list, ','))
  {
    const std::size_t first = item.find_first_not_of(" \t");
    if (first == std::string::npos)
      continue;
    item = item.substr(first, item.find_last_not_of(" \t") - first + 1);
    const std::size_t second = item.rfind(':');
    const std::size_t colon =
      second == std::string::npos || second == 0 ? std::string::npos : item.rfind(':', second - 1);
    CountEntry e;
    const long long most = std::numeric_limits<long long>::max() / 4;
    if (colon == std::string::npos || colon == 0 ||
      !ParseInteger(
        std::string(SplitText(item.substr(colon + 1, second - colon - 1), ':', true)[0]), 0, most,
        e.Minimum) ||
      !ParseInteger(SplitText(item.substr(second + 1), ':', true)[0], 0, most, e.Maximum) ||
      e.Maximum < e.Minimum)
      throw Error(what + ": '" + item + "' is not 'label:min:max' with 0 <= min <= max");
    e.Name = item.substr(0, colon);
    e.Name = e.Name.substr(0, e.Name.find_last_not_of(" \t") + 1);
    entries.push_back(e);
  }
  return entries;
}

} // namespace msynth
