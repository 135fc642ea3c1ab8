// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/OverlappingModel.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <unordered_set>

namespace msynth
{
namespace
{
using WindowCells = std::vector<std::uint16_t>;

/// The window of @p set's sample with top-left pixel (@p x, @p y), wrapping around its edges.
WindowCells Window(const PatternSet& set, int x, int y)
{
  const int n = set.Options.N;
  WindowCells w(ToIndex(n * n));
  for (int dy = 0; dy < n; ++dy)
    for (int dx = 0; dx < n; ++dx)
      w[ToIndex(dy * n + dx)] = set.Sample[ToIndex(
        ((y + dy) % set.SampleHeight) * set.SampleWidth + (x + dx) % set.SampleWidth)];
  return w;
}

/// The window turned a quarter: new (x, y) is old (N − 1 − y, x), as WaveFunctionCollapse turns.
WindowCells Turned(const WindowCells& p, int n)
{
  WindowCells r(p.size());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      r[ToIndex(y * n + x)] = p[ToIndex(x * n + n - 1 - y)];
  return r;
}

/// The window mirrored left-right.
WindowCells Mirrored(const WindowCells& p, int n)
{
  WindowCells r(p.size());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      r[ToIndex(y * n + x)] = p[ToIndex(y * n + n - 1 - x)];
  return r;
}

std::string Key(const std::uint16_t* cells, int columns0, int columns1, int rows0, int rows1, int n)
{
  std::string key;
  for (int y = rows0; y < rows1; ++y)
    for (int x = columns0; x < columns1; ++x)
    {
      const std::uint16_t c = cells[y * n + x];
      key.push_back(static_cast<char>(c & 0xff));
      key.push_back(static_cast<char>(c >> 8));
    }
  return key;
}

void CheckOptions(const RgbaImage& sample, const OverlappingOptions& o, const std::string& name)
{
  if (o.N < 1 || o.N > 8)
    throw Error(
      "'" + name + "': the pattern size must be between 1 and 8, not " + std::to_string(o.N));
  if (o.Symmetry < 1 || o.Symmetry > 8)
    throw Error("'" + name + "': the pattern symmetry must be between 1 and 8, not " +
      std::to_string(o.Symmetry));
  if (static_cast<std::int64_t>(sample.Width) * sample.Height > MaximumSamplePixels)
    throw Error("'" + name + "': the sample has " + std::to_string(sample.Width) + " x " +
      std::to_string(sample.Height) +
      " pixels; image samples are at most 2^20 pixels (every "
      "window of every symmetry is read)");
  if (sample.Width < 1 || sample.Height < 1 || o.N > sample.Width || o.N > sample.Height)
    throw Error("'" + name + "': the sample (" + std::to_string(sample.Width) + " x " +
      std::to_string(sample.Height) + " pixels) is smaller than a " + std::to_string(o.N) + " x " +
      std::to_string(o.N) + " pattern");
}

/// The sample as colour indices, colours numbered by first appearance.
void IndexColours(const RgbaImage& sample, PatternSet& set, const std::string& name)
{
  std::unordered_map<std::uint32_t, std::uint16_t> index;
  set.Sample.resize(ToIndex(sample.Width) * ToIndex(sample.Height));
  for (std::size_t i = 0; i < set.Sample.size(); ++i)
  {
    const std::uint8_t* p = sample.Pixels.data() + 4 * i;
    const std::uint32_t rgba = p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24);
    auto it = index.find(rgba);
    if (it == index.end())
    {
      if (set.Colours.size() >= 65536)
        throw Error("'" + name + "': the sample has more than 65536 colours");
      it = index.emplace(rgba, static_cast<std::uint16_t>(set.Colours.size())).first;
      set.Colours.push_back({ { p[0], p[1], p[2], p[3] } });
    }
    set.Sample[i] = it->second;
  }
}

/// Pairs along x (columns 1..N−1 of b equal columns 0..N−2 of c) and along y, up (rows 0..N−2
/// of b, from the top, equal rows 1..N−1 of c: c lies above b).
void FindPairs(PatternSet& set, const std::string& name)
{
  const int n = set.Options.N;
  const int k = set.NumberOfPatterns();
  std::size_t total = 0;
  for (int axis = 0; axis < 2; ++axis)
  {
    std::unordered_map<std::string, std::vector<int>> byLeading;
    for (int c = 0; c < k; ++c)
    {
      const std::uint16_t* cells = set.Cells.data() + ToIndex(c * n * n);
      byLeading[axis == 0 ? Key(cells, 0, n - 1, 0, n, n) : Key(cells, 0, n, 1, n, n)].push_back(c);
    }
    for (int b = 0; b < k; ++b)
    {
      const std::uint16_t* cells = set.Cells.data() + ToIndex(b * n * n);
      const auto it =
        byLeading.find(axis == 0 ? Key(cells, 1, n, 0, n, n) : Key(cells, 0, n, 0, n - 1, n));
      if (it == byLeading.end())
        continue;
      total += it->second.size();
      if (total > (std::size_t(1) << 26))
        throw Error("'" + name + "': the sample's " + std::to_string(k) +
          " patterns have more than 2^26 neighbour pairs; use a larger pattern size");
      for (const int c : it->second)
        set.Pairs[ToIndex(axis)].emplace_back(b, c);
    }
  }
}
} // namespace

PatternSet ExtractPatterns(
  const RgbaImage& sample, const OverlappingOptions& options, const std::string& name)
{
  CheckOptions(sample, options, name);
  PatternSet set;
  set.Options = options;
  set.SampleWidth = sample.Width;
  set.SampleHeight = sample.Height;
  IndexColours(sample, set, name);
  const int n = options.N;
  const int xmax = options.PeriodicInput ? sample.Width : sample.Width - n + 1;
  const int ymax = options.PeriodicInput ? sample.Height : sample.Height - n + 1;
  std::unordered_map<std::string, int> index;
  set.WindowPatterns.assign(set.Sample.size(), -1);
  for (int y = 0; y < ymax; ++y)
    for (int x = 0; x < xmax; ++x)
    {
      std::array<WindowCells, 8> images;
      images[0] = Window(set, x, y);
      for (int j = 1; j < 4; ++j)
        images[ToIndex(2 * j)] = Turned(images[ToIndex(2 * j - 2)], n);
      for (int j = 0; j < 4; ++j)
        images[ToIndex(2 * j + 1)] = Mirrored(images[ToIndex(2 * j)], n);
      for (int s = 0; s < options.Symmetry; ++s)
      {
        const WindowCells& p = images[ToIndex(s)];
        const std::string key = Key(p.data(), 0, n, 0, n, n);
        const auto it = index.find(key);
        if (s == 0)
          set.WindowPatterns[ToIndex(y * sample.Width + x)] =
            it != index.end() ? it->second : set.NumberOfPatterns();
        if (it != index.end())
        {
          set.Counts[ToIndex(it->second)] += 1.0;
          continue;
        }
        if (set.NumberOfPatterns() >= MaximumPatterns)
          throw Error("'" + name + "': the sample has more than " +
            std::to_string(MaximumPatterns) + " different " + std::to_string(n) + " x " +
            std::to_string(n) +
            " patterns; use a smaller pattern size, less symmetry or a sample with fewer colours");
        index.emplace(key, set.NumberOfPatterns());
        set.Counts.push_back(1.0);
        set.Cells.insert(set.Cells.end(), p.begin(), p.end());
      }
    }
  FindPairs(set, name);
  return set;
}

AdjacencyRules PatternSet::Rules() const
{
  std::vector<Label> values(ToIndex(this->NumberOfPatterns()));
  for (std::size_t t = 0; t < values.size(); ++t)
    values[t] = static_cast<Label>(t);
  return AdjacencyRules::FromPairs(std::move(values), this->Counts, this->Pairs);
}

std::array<std::int64_t, 3> PatternSet::SitesFor(
  std::int64_t width, std::int64_t height, const Periodic& periodic) const
{
  const int n = this->Options.N;
  if (width < n || height < n)
    throw Error("the picture (" + std::to_string(width) + " x " + std::to_string(height) +
      " pixels) is smaller than a " + std::to_string(n) + " x " + std::to_string(n) + " pattern");
  return { { periodic[0] ? width : width - n + 1, periodic[1] ? height : height - n + 1, 1 } };
}

std::vector<int> PatternSet::GroundPatterns(bool periodicY) const
{
  const int n = this->Options.N;
  if (periodicY && !this->Options.PeriodicInput && n > 1)
    throw Error("a ground for a repeating output is the sample's window that starts on its "
                "last row and wraps to its top, which needs a periodic input");
  // The windows read on the ground row (all of it bounded, its middle repeating).
  const int y = periodicY ? this->SampleHeight - 1 : this->SampleHeight - n;
  const int first = periodicY ? this->SampleWidth / 2 : 0;
  const int last = periodicY      ? first + 1
    : this->Options.PeriodicInput ? this->SampleWidth
                                  : this->SampleWidth - n + 1;
  std::vector<int> ground;
  for (int x = first; x < last; ++x)
  {
    const int t = this->WindowPatterns[ToIndex(y * this->SampleWidth + x)];
    if (std::find(ground.begin(), ground.end(), t) == ground.end())
      ground.push_back(t);
  }
  return ground;
}

GuideVolume PatternSet::GroundGuide(const std::array<std::int64_t, 3>& sites, bool periodicY) const
{
  const std::vector<int> ground = this->GroundPatterns(periodicY);
  const std::int64_t rows = sites[1];
  CheckMemory(
    static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(this->NumberOfPatterns()) * 8u,
    "the ground constraint of " + std::to_string(rows) + " rows of " +
      std::to_string(this->NumberOfPatterns()) + " patterns");
  GuideVolume guide;
  guide.Dims = { { 1, rows, 1 } };
  for (int t = 0; t < this->NumberOfPatterns(); ++t)
  {
    const bool isGround = std::find(ground.begin(), ground.end(), t) != ground.end();
    std::vector<float> w(ToIndex(rows), isGround ? 0.0f : 1.0f);
    w[0] = isGround ? 1.0f : 0.0f;
    guide.Weights.emplace(static_cast<Label>(t), std::move(w));
  }
  return guide;
}

std::optional<LabelGrid> PatternSet::TiledStart(
  const std::array<std::int64_t, 3>& sites, const Periodic& periodic) const
{
  const std::int64_t sw = this->SampleWidth, sh = this->SampleHeight;
  if (!this->Options.PeriodicInput || this->Options.Ground || (periodic[0] && sites[0] % sw) ||
    (periodic[1] && sites[1] % sh) || sites[2] != 1)
    return std::nullopt;
  LabelGrid start(sites[0], sites[1], 1);
  for (std::int64_t y = 0; y < sites[1]; ++y)
    for (std::int64_t x = 0; x < sites[0]; ++x)
      start.Set(x, y, 0, this->WindowPatterns[ToIndex(((sites[1] - 1 - y) % sh) * sw + x % sw)]);
  return start;
}

void PatternSet::Configure(SynthesisOptions& options, const Periodic& periodic) const
{
  if (this->Options.Ground)
  {
    if (options.Guide)
      throw Error("the ground is a guide of its own: it cannot be combined with a guide");
    options.Guide = this->GroundGuide(options.Size, periodic[1]);
  }
  bool blocks = false;
  for (int a = 0; a < 3; ++a)
    blocks |= options.BlockSize[a] > 0 && options.BlockSize[a] < options.Size[a];
  // The sample tiled holds every pattern somewhere, so a guide that forbids one would refuse it:
  // with a guide the start is the solver's own (a trivial label or layers the guide allows).
  if (!blocks || options.TrivialLabel || options.Start)
    return;
  // The sample tiled brings the sample's own wrap into every block's ring (Rooms: a double wall
  // along two of its edges), and a block must continue what its ring holds: a straight feature
  // of the wrap runs on through every block along the borders, a seam through the picture
  // (issue 44). Where the output does not repeat, an undecided start gives the blocks no such
  // ring (and a region can compute it), the tiled one only where it fails; a repeating output
  // keeps the tiled start, since an undecided one cannot close its seam.
  options.UndecidedFirst = !periodic[0] && !periodic[1];
  if (!options.Guide)
    options.Start = this->TiledStart(options.Size, periodic);
}

RgbaImage PatternSet::Compose(const LabelGrid& model, const Periodic& periodic) const
{
  const int n = this->Options.N;
  const std::int64_t sx = model.Size(0), sy = model.Size(1);
  RgbaImage picture;
  const std::int64_t w = periodic[0] ? sx : sx + n - 1;
  const std::int64_t h = periodic[1] ? sy : sy + n - 1;
  if (model.Size(2) != 1 || w * h > MaximumImagePixels || w > 65536 || h > 65536)
    throw Error("a picture of " + std::to_string(w) + " x " + std::to_string(h) + " x " +
      std::to_string(model.Size(2)) + " pixels cannot be made (2D, at most 2^26 pixels)");
  picture.Width = static_cast<int>(w);
  picture.Height = static_cast<int>(h);
  picture.Pixels.resize(ToIndex(w * h * 4));
  for (std::int64_t py = 0; py < h; ++py)
    for (std::int64_t px = 0; px < w; ++px)
    {
      const std::int64_t x = std::min(px, sx - 1), row = std::min(py, sy - 1);
      const Label t = model.At(x, sy - 1 - row, 0);
      if (t < 0 || t >= this->NumberOfPatterns())
        throw Error("the model has label " + std::to_string(t) + ", which is not one of the " +
          std::to_string(this->NumberOfPatterns()) + " patterns");
      const auto& c =
        this->Colours[this->At(t, static_cast<int>(px - x), static_cast<int>(py - row))];
      std::copy(c.begin(), c.end(), picture.Pixels.begin() + 4 * (py * w + px));
    }
  return picture;
}

LabelGrid PatternSet::PinsFromPicture(
  const RgbaImage& picture, const std::string& path, const Periodic& periodic) const
{
  const int n = this->Options.N;
  std::array<std::int64_t, 3> sites;
  try
  {
    sites = this->SitesFor(picture.Width, picture.Height, periodic);
  }
  catch (const Error& e)
  {
    throw Error::InFile(path, e.what());
  }
  // Each pixel's colour index; -1 where free (transparent in a colour the sample lacks).
  std::map<std::array<std::uint8_t, 4>, int> index;
  for (std::size_t c = 0; c < this->Colours.size(); ++c)
    index[this->Colours[c]] = static_cast<int>(c);
  std::vector<int> colour(ToIndex(picture.Width) * ToIndex(picture.Height));
  for (int y = 0; y < picture.Height; ++y)
    for (int x = 0; x < picture.Width; ++x)
    {
      const std::uint8_t* p = picture.At(x, y);
      const auto found = index.find({ { p[0], p[1], p[2], p[3] } });
      int& c = colour[ToIndex(y) * ToIndex(picture.Width) + ToIndex(x)];
      c = found != index.end() ? found->second : -1;
      if (c < 0 && p[3] != 0)
        throw Error::InFile(path,
          "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
            ") has a colour the sample does not have (and is not transparent)");
    }
  std::map<std::vector<std::uint16_t>, Label> byCells;
  for (int t = this->NumberOfPatterns(); t-- > 0;)
    byCells[std::vector<std::uint16_t>(this->Cells.begin() + static_cast<std::ptrdiff_t>(t) * n * n,
      this->Cells.begin() + static_cast<std::ptrdiff_t>(t + 1) * n * n)] = t;
  LabelGrid pins(sites[0], sites[1], 1, Label(-1));
  std::vector<std::uint16_t> window(ToIndex(n) * ToIndex(n));
  for (std::int64_t row = 0; row < sites[1]; ++row)
    for (std::int64_t x = 0; x < sites[0]; ++x)
    {
      bool drawn = true;
      for (int j = 0; j < n && drawn; ++j)
        for (int i = 0; i < n && drawn; ++i)
        {
          const std::int64_t px = (x + i) % picture.Width, py = (row + j) % picture.Height;
          const int c = colour[ToIndex(py * picture.Width + px)];
          drawn = c >= 0;
          window[ToIndex(j * n + i)] = static_cast<std::uint16_t>(drawn ? c : 0);
        }
      if (!drawn)
        continue;
      const auto found = byCells.find(window);
      if (found == byCells.end())
        throw Error::InFile(path,
          "the " + std::to_string(n) + " x " + std::to_string(n) + " window at pixel (" +
            std::to_string(x) + ", " + std::to_string(row) + ") is none of the sample's patterns");
      pins.Set(x, sites[1] - 1 - row, 0, found->second);
    }
  return pins;
}

// ---------------------------------------------------------------------------------------------
// The independent check: windows of RGBA pixels, compared as bytes.
// ---------------------------------------------------------------------------------------------
namespace
{
/// Pixel (x, y) of dihedral image @p k (0-7, WaveFunctionCollapse's order: even k turns k/2
/// quarters, odd k mirrors that turn left-right) of an N × N window, as coordinates in the window.
std::pair<int, int> SourceOf(int k, int x, int y, int n)
{
  if (k % 2 == 1)
    x = n - 1 - x;
  for (int j = 0; j < k / 2; ++j)
  {
    const int px = n - 1 - y, py = x; // a turned window's (x, y) is the window's (N−1−y, x)
    x = px;
    y = py;
  }
  return { x, y };
}

std::string WindowBytes(const RgbaImage& image, int x0, int y0, int k, int n)
{
  std::string bytes;
  bytes.reserve(ToIndex(4 * n * n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
    {
      const auto s = SourceOf(k, x, y, n);
      const std::uint8_t* p =
        image.At((x0 + s.first) % image.Width, (y0 + s.second) % image.Height);
      bytes.append(reinterpret_cast<const char*>(p), 4);
    }
  return bytes;
}
} // namespace

std::vector<std::string> CheckPicture(const RgbaImage& sample, const OverlappingOptions& options,
  const RgbaImage& picture, const Periodic& periodic, std::size_t limit)
{
  const int n = options.N;
  std::vector<std::string> problems;
  if (picture.Width < n || picture.Height < n)
    return { "the picture is smaller than a pattern" };
  std::unordered_set<std::string> windows;
  const int xs = options.PeriodicInput ? sample.Width : sample.Width - n + 1;
  const int ys = options.PeriodicInput ? sample.Height : sample.Height - n + 1;
  for (int y = 0; y < ys; ++y)
    for (int x = 0; x < xs; ++x)
      for (int k = 0; k < options.Symmetry; ++k)
        windows.insert(WindowBytes(sample, x, y, k, n));
  std::unordered_set<std::string> ground;
  int groundRow = -1;
  if (options.Ground)
  {
    // WaveFunctionCollapse's ground: the bottom-middle window, wrapping; bounded, the last rows.
    if (periodic[1])
      ground.insert(WindowBytes(sample, sample.Width / 2, sample.Height - 1, 0, n));
    else
      for (int x = 0; x < xs; ++x)
        ground.insert(WindowBytes(sample, x, sample.Height - n, 0, n));
    groundRow = periodic[1] ? picture.Height - 1 : picture.Height - n;
  }
  const int xe = periodic[0] ? picture.Width : picture.Width - n + 1;
  const int ye = periodic[1] ? picture.Height : picture.Height - n + 1;
  for (int y = 0; y < ye && problems.size() < limit; ++y)
    for (int x = 0; x < xe && problems.size() < limit; ++x)
    {
      const std::string w = WindowBytes(picture, x, y, 0, n);
      const std::string at = " at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
      if (!windows.count(w))
        problems.push_back("the window" + at + " is not in the sample");
      else if (options.Ground && (y == groundRow) != (ground.count(w) > 0))
        problems.push_back(y == groundRow ? "the window" + at + " of the bottom row is not ground"
                                          : "the ground window appears" + at);
    }
  return problems;
}

} // namespace msynth
