// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Xml.h
 * @brief A small XML reader (internal): elements, attributes and character data; comments,
 * processing instructions and declarations are skipped. Errors name the file and line. Used by
 * the tileset reader and the VTK XML file check.
 */
#include "Core/Error.h"

#include <cctype>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{
namespace detail
{

struct XmlElement
{
  std::string Name;
  std::string Text; ///< the character data directly inside the element (entities not decoded)
  std::vector<std::pair<std::string, std::string>> Attributes;
  std::vector<XmlElement> Children;
  int Line = 0;

  const std::string* Attribute(const std::string& key) const
  {
    for (const auto& kv : this->Attributes)
      if (kv.first == key)
        return &kv.second;
    return nullptr;
  }
};

class XmlReader
{
public:
  XmlReader(std::string text, const std::string& name)
    : Text(std::move(text))
    , Name(name)
  {
  }

  [[noreturn]] void Fail(const std::string& problem, int line = -1) const
  {
    throw Error("'" + this->Name + "', line " + std::to_string(line < 0 ? this->Line : line) +
      ": " + problem);
  }

  XmlElement Parse()
  {
    std::vector<XmlElement> stack;
    std::vector<XmlElement> roots;
    while (this->Pos < this->Text.size())
    {
      const char c = this->Text[this->Pos];
      if (c != '<')
      {
        if (!stack.empty())
          stack.back().Text += c;
        this->Advance(1);
        continue;
      }
      if (this->StartsWith("<?"))
        this->SkipPast("?>");
      else if (this->StartsWith("<!--"))
        this->SkipPast("-->");
      else if (this->StartsWith("<!"))
        this->SkipPast(">");
      else if (this->StartsWith("</"))
      {
        this->Advance(2);
        const std::string name = this->ReadName();
        this->SkipSpace();
        this->Expect('>');
        if (stack.empty() || stack.back().Name != name)
          this->Fail("closing tag </" + name + "> does not match " +
            (stack.empty() ? std::string("any open element") : "<" + stack.back().Name + ">"));
        XmlElement done = std::move(stack.back());
        stack.pop_back();
        (stack.empty() ? roots : stack.back().Children).push_back(std::move(done));
      }
      else
      {
        this->Advance(1);
        XmlElement e;
        e.Line = this->Line;
        e.Name = this->ReadName();
        bool selfClosing = false;
        for (;;)
        {
          this->SkipSpace();
          if (this->StartsWith("/>"))
          {
            this->Advance(2);
            selfClosing = true;
            break;
          }
          if (this->StartsWith(">"))
          {
            this->Advance(1);
            break;
          }
          const std::string key = this->ReadName();
          this->SkipSpace();
          this->Expect('=');
          this->SkipSpace();
          e.Attributes.emplace_back(key, this->ReadQuoted());
        }
        if (selfClosing)
          (stack.empty() ? roots : stack.back().Children).push_back(std::move(e));
        else
        {
          if (stack.size() >= 64)
            this->Fail("elements are nested more than 64 deep");
          stack.push_back(std::move(e));
        }
      }
    }
    if (!stack.empty())
      this->Fail("the file ends inside <" + stack.back().Name + ">", stack.back().Line);
    if (roots.size() != 1)
      this->Fail(roots.empty() ? "no XML element found" : "more than one top-level element");
    return std::move(roots.front());
  }

private:
  bool StartsWith(const char* s) const
  {
    return this->Text.compare(this->Pos, std::strlen(s), s) == 0;
  }
  void Advance(std::size_t n)
  {
    for (std::size_t i = 0; i < n && this->Pos < this->Text.size(); ++i)
      this->Line += this->Text[this->Pos++] == '\n';
  }
  void SkipPast(const char* end)
  {
    const std::size_t at = this->Text.find(end, this->Pos);
    if (at == std::string::npos)
      this->Fail(std::string("unterminated markup (no '") + end + "')");
    this->Advance(at + std::strlen(end) - this->Pos);
  }
  void SkipSpace()
  {
    while (this->Pos < this->Text.size() &&
      std::isspace(static_cast<unsigned char>(this->Text[this->Pos])))
      this->Advance(1);
  }
  void Expect(char c)
  {
    if (this->Pos >= this->Text.size() || this->Text[this->Pos] != c)
      this->Fail(std::string("expected '") + c + "'");
    this->Advance(1);
  }
  std::string ReadName()
  {
    const std::size_t start = this->Pos;
    while (this->Pos < this->Text.size() &&
      (std::isalnum(static_cast<unsigned char>(this->Text[this->Pos])) ||
        std::strchr("_-.:", this->Text[this->Pos])))
      this->Advance(1);
    if (this->Pos == start)
      this->Fail("expected a name");
    return this->Text.substr(start, this->Pos - start);
  }
  std::string ReadQuoted()
  {
    if (this->Pos >= this->Text.size() ||
      (this->Text[this->Pos] != '"' && this->Text[this->Pos] != '\''))
      this->Fail("expected a quoted attribute value");
    const char quote = this->Text[this->Pos];
    this->Advance(1);
    std::string value;
    while (this->Pos < this->Text.size() && this->Text[this->Pos] != quote)
    {
      if (this->Text[this->Pos] == '&')
      {
        static const std::pair<const char*, char> entities[] = { { "&amp;", '&' }, { "&lt;", '<' },
          { "&gt;", '>' }, { "&quot;", '"' }, { "&apos;", '\'' } };
        bool known = false;
        for (const auto& en : entities)
          if (this->StartsWith(en.first))
          {
            value += en.second;
            this->Advance(std::strlen(en.first));
            known = true;
            break;
          }
        if (!known)
          this->Fail("unknown entity in an attribute value");
        continue;
      }
      value += this->Text[this->Pos];
      this->Advance(1);
    }
    if (this->Pos >= this->Text.size())
      this->Fail("unterminated attribute value");
    this->Advance(1);
    return value;
  }

  std::string Text;
  const std::string& Name;
  std::size_t Pos = 0;
  int Line = 1;
};

} // namespace detail
} // namespace msynth
