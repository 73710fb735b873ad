#include "python/run_data.hpp"

#include <algorithm>
#include <stdexcept>

namespace tongue::python {

namespace layout = run_file::layout;

RunData::RunData(const std::string& path) : reader_(path) {}

Dataset RunData::dataset(const std::string& name) const {
  return {reader_.doubles(name), reader_.shape(name)};
}

std::vector<std::string> RunData::muscle_names() const {
  return reader_.exists(layout::kMuscleNames) ? reader_.strings(layout::kMuscleNames)
                                              : std::vector<std::string>{};
}

std::vector<double> RunData::muscle_series(const std::string& dataset,
                                           const std::string& muscle) const {
  const std::vector<std::string> names = muscle_names();
  const auto at = std::find(names.begin(), names.end(), muscle);
  if (at == names.end())
    throw std::invalid_argument(path() + ": no muscle '" + muscle + "' in the run");
  const Dataset d = this->dataset(dataset);
  if (d.shape.size() != 2 || d.shape[1] != names.size())
    throw std::invalid_argument(path() + ": " + dataset + " is not a frames x muscles dataset");
  const std::size_t m = static_cast<std::size_t>(at - names.begin());
  std::vector<double> series(d.shape[0]);
  for (std::size_t t = 0; t < d.shape[0]; ++t) series[t] = d.values[t * names.size() + m];
  return series;
}

std::string RunData::status() const {
  return reader_.has_attribute(layout::kRoot, layout::kStatusAttribute)
             ? reader_.string_attribute(layout::kRoot, layout::kStatusAttribute)
             : std::string();
}

}  // namespace tongue::python
