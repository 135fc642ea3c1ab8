// SPDX-License-Identifier: BSD-3-Clause
#include "HelpText.h"
#include "Core/Index.h"

#include <algorithm>
#include <iterator>
#include <sstream>

namespace msynth
{
namespace cli
{
namespace
{
/// What a user types for one value of @p option: its choices ("auto|trivial"), a name the
/// command gave ("KINDS", "A:B"), N for whole numbers, X for numbers, else VALUE.
std::string ValueName(const CLI::Option* option)
{
  const std::string type = option->get_type_name();
  const std::size_t open = type.find('{'), close = type.find('}');
  if (open != std::string::npos && close != std::string::npos && close > open)
  {
    std::string choices = type.substr(open + 1, close - open - 1);
    std::replace(choices.begin(), choices.end(), ',', '|');
    return choices;
  }
  const std::string head = type.substr(0, type.find(':'));
  if (head == "INT" || head == "UINT")
    return "N";
  if (head == "FLOAT")
    return "X";
  if (head == "TEXT" || head.empty())
    return type.find(':') != std::string::npos ? type.substr(type.find(':') + 1) : "VALUE";
  return head; // a name the command chose (KINDS, A:B, AXES, ...)
}

/// The @p count value names the description gives ("size NX NY NZ", "write E_I to FILE"):
/// @p count consecutive capitalized words, or for one value a word such as DIR or FILE; empty
/// when it gives none.
std::vector<std::string> DescribedNames(const std::string& description, int count)
{
  std::istringstream words(description);
  std::vector<std::string> run;
  std::string word;
  static const char* const single[] = { "DIR", "FILE", "NAME", "LABEL", "LABELS", "PATH" };
  while (words >> word)
  {
    if (count == 1 && word.rfind("DIR/", 0) == 0) // "DIR/<label>.obj": a folder
      return { "DIR" };
    while (!word.empty() && std::string(",.;:)").find(word.back()) != std::string::npos)
      word.pop_back();
    const bool capital = word.size() >= 2 && word.size() <= 6 &&
      std::all_of(word.begin(), word.end(),
        [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
    if (count == 1 && capital &&
      std::any_of(std::begin(single), std::end(single), [&](const char* n) { return word == n; }))
      return { word };
    if (!capital)
      run.clear();
    else if (count > 1)
    {
      run.push_back(word);
      if (static_cast<int>(run.size()) == count)
        return run;
    }
  }
  if (count == 1 && description.find("folder") != std::string::npos)
    return { "DIR" };
  if (count == 1 &&
    (description.find(" file") != std::string::npos ||
      description.find(".vti") != std::string::npos))
    return { "FILE" };
  return {};
}

class HelpFormatter : public CLI::Formatter
{
public:
  std::string make_option_opts(const CLI::Option* option) const override
  {
    if (!option->get_option_text().empty())
      return " " + option->get_option_text();
    if (option->get_type_size() == 0 || option->get_expected_max() == 0 || option->get_positional())
      return ""; // a flag, or a positional named by its name
    std::ostringstream out;
    const std::string value = ValueName(option);
    const int count = option->get_expected_max() == CLI::detail::expected_max_vector_size
      ? 1
      : std::max(1, option->get_expected_min());
    const bool generic = value == "N" || value == "X" || value == "VALUE";
    std::vector<std::string> named =
      generic ? DescribedNames(option->get_description(), count) : std::vector<std::string>();
    if (value != "VALUE" && named.size() == 1 && (named[0] == "DIR" || named[0] == "FILE"))
      named.clear(); // a number is no folder
    for (int i = 0; i < count; ++i)
      out << " " << (named.empty() ? value : named[msynth::ToIndex(i)]);
    if (option->get_expected_max() == CLI::detail::expected_max_vector_size)
      out << " ... (repeatable)";
    const std::string fallback = option->get_default_str();
    // A default says something when it is one value the description does not give already.
    if (option->get_required())
      out << " (required)";
    else if (!fallback.empty() && fallback.front() != '[' &&
      option->get_description().find("default") == std::string::npos)
      out << " (default " << fallback << ")";
    return out.str();
  }
};

std::size_t EditDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t above = row[j];
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1]) });
      diagonal = above;
    }
  }
  return row[b.size()];
}
} // namespace

std::shared_ptr<CLI::Formatter> MakeHelpFormatter()
{
  auto formatter = std::make_shared<HelpFormatter>();
  formatter->column_width(34);
  return formatter;
}

std::string ClosestName(const std::string& typed, const std::vector<std::string>& names)
{
  std::string best;
  std::size_t distance = typed.size() / 3 + 1;
  for (const auto& name : names)
  {
    const std::size_t d = EditDistance(typed, name);
    if (d < distance)
    {
      distance = d;
      best = name;
    }
  }
  return best;
}

} // namespace cli
} // namespace msynth
