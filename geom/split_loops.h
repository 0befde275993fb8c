// Cutting a closed walk where it touches itself, shared by the exact map's boundary walks
// and the untangling of rounded rings.
#pragma once

#include <cstddef>
#include <unordered_map>
#include <vector>

namespace geom {

// Splits a closed walk that passes some vertex twice into loops that pass none twice;
// vertex_of(step) names the vertex a step leaves from.
template <typename Vertex, typename Hash = std::hash<Vertex>, typename Step, typename VertexOf>
std::vector<std::vector<Step>> split_at_repeats(const std::vector<Step>& walk, VertexOf vertex_of) {
  std::vector<std::vector<Step>> loops;
  std::vector<Step> stack;
  std::unordered_map<Vertex, std::size_t, Hash> position;  // vertex -> index in stack
  for (const Step& s : walk) {
    const Vertex v = vertex_of(s);
    auto it = position.find(v);
    if (it != position.end()) {
      const std::size_t k = it->second;
      loops.emplace_back(stack.begin() + static_cast<long>(k), stack.end());
      for (std::size_t i = k; i < stack.size(); ++i) position.erase(vertex_of(stack[i]));
      stack.resize(k);
    }
    position[v] = stack.size();
    stack.push_back(s);
  }
  if (!stack.empty()) loops.push_back(std::move(stack));
  return loops;
}

}  // namespace geom
