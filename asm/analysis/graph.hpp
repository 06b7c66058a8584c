// Strongly connected components (Tarjan, without recursion: call chains of a million regions
// must not overflow the C++ stack), over any graph given as a successor function. Used for the
// call graph (recursion, longest call chain) and the instruction graph (EEPROM writes in loops).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace tmcl::detail {

// Calls succ(v, out) for the successors of v: succ appends them to `out` (cleared first).
// Returns the component of every vertex of `roots`' reach (-1 elsewhere); components are
// numbered in the order Tarjan completes them, so every edge leads to a component with a
// number no larger than its own (callees before callers).
template <class Succ>
std::vector<int> strong_components(int n, const std::vector<int>& roots, Succ succ, int& count) {
  std::vector<int> index(static_cast<std::size_t>(n), -1), low(static_cast<std::size_t>(n), 0),
      comp(static_cast<std::size_t>(n), -1);
  std::vector<int> stack;
  struct Frame {
    int v;
    std::size_t begin;
    std::size_t next;  // position in `edges` of the next successor to look at
    std::size_t end;
  };
  std::vector<Frame> frames;
  std::vector<int> edges;  // successors of every open frame, one block per frame
  std::vector<int> scratch;
  int counter = 0;
  count = 0;
  auto open = [&](int v) {
    index[static_cast<std::size_t>(v)] = low[static_cast<std::size_t>(v)] = counter++;
    stack.push_back(v);
    scratch.clear();
    succ(v, scratch);
    std::size_t begin = edges.size();
    edges.insert(edges.end(), scratch.begin(), scratch.end());
    frames.push_back({v, begin, begin, edges.size()});
  };
  for (int root : roots) {
    if (root < 0 || root >= n || index[static_cast<std::size_t>(root)] >= 0) continue;
    open(root);
    while (!frames.empty()) {
      Frame& f = frames.back();
      if (f.next < f.end) {
        int w = edges[f.next++];
        if (w < 0 || w >= n) continue;
        if (index[static_cast<std::size_t>(w)] < 0) {
          open(w);
        } else if (comp[static_cast<std::size_t>(w)] < 0) {
          low[static_cast<std::size_t>(f.v)] = std::min(low[static_cast<std::size_t>(f.v)], index[static_cast<std::size_t>(w)]);
        }
        continue;
      }
      int v = f.v;
      edges.resize(f.begin);  // a finished frame's block is the last one
      frames.pop_back();
      if (low[static_cast<std::size_t>(v)] == index[static_cast<std::size_t>(v)]) {
        for (;;) {
          int w = stack.back();
          stack.pop_back();
          comp[static_cast<std::size_t>(w)] = count;
          if (w == v) break;
        }
        ++count;
      }
      if (!frames.empty()) {
        int p = frames.back().v;
        low[static_cast<std::size_t>(p)] = std::min(low[static_cast<std::size_t>(p)], low[static_cast<std::size_t>(v)]);
      }
    }
  }
  return comp;
}

}  // namespace tmcl::detail
