// The JSON form of a lab dataset: strict parsing and its inverse.
#include "orchestrator/diagnosis/dataset/dataset.hpp"

#include <map>

#include "orchestrator/calibration/lab_case.hpp"
#include "orchestrator/json_fields.hpp"

namespace rockcal::diagnosis {
namespace {

using nlohmann::json;

std::string required_string(orch::JsonFields& f, const std::string& key) {
  auto s = f.string(key);
  if (!s) throw orch::RequestError(f.path_of(key), "is required");
  if (s->empty()) throw orch::RequestError(f.path_of(key), "must not be empty");
  return *s;
}

TestKind parse_test(orch::JsonFields& f) {
  const std::string name = required_string(f, "test");
  const auto kind = test_kind_from_string(name);
  if (!kind || *kind == TestKind::elastic) {
    throw orch::RequestError(f.path_of("test"),
                             "unknown test '" + name + "' (known: uct, btt, triaxial)");
  }
  return *kind;
}

Observable parse_observable(orch::JsonFields& f, TestKind test) {
  const std::string name = required_string(f, "observable");
  for (Observable o : {Observable::peak_load, Observable::strength, Observable::youngs_modulus,
                       Observable::peak_strain}) {
    if (name != to_string(o)) continue;
    // The engine measures E (the pre-peak slope) and the strain at peak on the compressed
    // cylinder only.
    const bool axial = o == Observable::youngs_modulus || o == Observable::peak_strain;
    if (axial && test == TestKind::btt) {
      throw orch::RequestError(f.path_of("observable"),
                               std::string(to_string(o)) + " is measured by uct or triaxial");
    }
    return o;
  }
  throw orch::RequestError(f.path_of("observable"),
                           "unknown observable '" + name +
                               "' (known: peak_load, strength, youngs_modulus, peak_strain)");
}

Role parse_role(orch::JsonFields& f) {
  const std::string name = required_string(f, "role");
  if (name == "calibration") return Role::calibration;
  if (name == "held_out") return Role::held_out;
  throw orch::RequestError(f.path_of("role"), "must be calibration or held_out");
}

// Each dimension belongs to one specimen shape, and the confining pressure to the triaxial test
// alone: a stray key is far more likely a mistake than something to ignore.
Conditions parse_conditions(orch::JsonFields& obs, TestKind test) {
  Conditions c;
  const json* v = obs.get("conditions");
  const bool triaxial = is_triaxial(test);
  if (!v) {
    if (triaxial) {
      throw orch::RequestError(obs.path_of("conditions.confining_pressure"),
                               "is required for a triaxial test");
    }
    return c;
  }
  orch::JsonFields f(*v, obs.path_of("conditions"));
  c.diameter_m = f.positive("diameter");
  c.height_m = f.positive("height");
  c.thickness_m = f.positive("thickness");
  const auto pressure = f.positive("confining_pressure");
  c.loading_rate_m_s = f.positive("loading_rate");
  f.reject_unknown();
  if (test == TestKind::btt && c.height_m) {
    throw orch::RequestError(f.path_of("height"), "a btt disc has no height (give thickness)");
  }
  if (test != TestKind::btt && c.thickness_m) {
    throw orch::RequestError(f.path_of("thickness"), "only a btt disc has a thickness");
  }
  if (triaxial && !pressure) {
    throw orch::RequestError(f.path_of("confining_pressure"), "is required for a triaxial test");
  }
  if (!triaxial && pressure) {
    throw orch::RequestError(
        f.path_of("confining_pressure"),
        std::string("only a triaxial test has one (this is a ") + to_string(test) + ")");
  }
  c.confining_pressure_pa = pressure.value_or(0.0);
  return c;
}

std::vector<Observation> parse_observations(orch::JsonFields& root) {
  const json& list = root.require("observations");
  if (!list.is_array() || list.empty()) {
    throw orch::RequestError("observations", "must be a non-empty list");
  }
  std::vector<Observation> observations;
  std::map<std::string, std::size_t> index_of_id;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "observations[" + std::to_string(i) + "]";
    observations.push_back(parse_observation(list[i], path));
    const auto [it, fresh] = index_of_id.emplace(observations.back().id, i);
    if (!fresh) {
      throw orch::RequestError(path + ".id", "duplicate id '" + it->first +
                                                 "' (also observations[" +
                                                 std::to_string(it->second) + "])");
    }
  }
  bool any_calibration = false;
  for (const Observation& o : observations) any_calibration |= o.role == Role::calibration;
  if (!any_calibration) {
    throw orch::RequestError("observations", "no observation has role calibration");
  }
  return observations;
}

json conditions_json(const Observation& o) {
  json c = json::object();
  const Conditions& k = o.conditions;
  if (k.diameter_m) c["diameter"] = *k.diameter_m;
  if (k.height_m) c["height"] = *k.height_m;
  if (k.thickness_m) c["thickness"] = *k.thickness_m;
  if (is_triaxial(o.test)) c["confining_pressure"] = k.confining_pressure_pa;
  if (k.loading_rate_m_s) c["loading_rate"] = *k.loading_rate_m_s;
  return c;
}

}  // namespace

Observation parse_observation(const json& j, const std::string& path) {
  orch::JsonFields f(j, path);
  Observation o;
  o.id = required_string(f, "id");
  o.test = parse_test(f);
  o.conditions = parse_conditions(f, o.test);
  o.observable = parse_observable(f, o.test);
  o.value = f.required_positive("value");
  o.uncertainty = f.required_positive("uncertainty");
  o.role = parse_role(f);
  f.reject_unknown();
  return o;
}

Dataset parse_dataset_json(const json& j) {
  orch::JsonFields root(j, "");
  Dataset d;
  d.name = root.string("name").value_or("");
  d.note = root.string("note").value_or("");
  d.source = root.string("source").value_or("");
  const std::string origin = root.string("origin").value_or("lab");
  if (origin == "same_resolution_model") {
    d.origin = Origin::same_resolution_model;
  } else if (origin == "finer_model") {
    d.origin = Origin::finer_model;
  } else if (origin != "lab") {
    throw orch::RequestError("origin",
                             "must be \"lab\", \"same_resolution_model\" or \"finer_model\"");
  }
  const std::string units = root.string("units").value_or("model");
  if (units == "lab") {
    // No job template here: model_scale states K_r, R and rho itself (check_model_scale compares
    // them with the template later).
    d.lab = calibration::parse_lab_case(root, std::nullopt);
    d.scaling = make_scaling(d.lab->material, d.lab->model, d.lab->length_ratio);
  } else if (units != "model") {
    throw orch::RequestError("units", "must be \"model\" or \"lab\"");
  } else if (root.get("lab") || root.get("model_scale")) {
    throw orch::RequestError("units", "must be \"lab\" when lab and model_scale are given");
  }
  d.observations = parse_observations(root);
  root.reject_unknown();
  return d;
}

json to_json(const Dataset& d) {
  json j = {{"name", d.name}};
  if (!d.note.empty()) j["note"] = d.note;
  if (!d.source.empty()) j["source"] = d.source;
  j["origin"] = to_string(d.origin);
  j["units"] = d.lab ? "lab" : "model";
  if (d.lab) j.update(calibration::lab_case_json(*d.lab));
  json list = json::array();
  for (const Observation& o : d.observations) {
    json obs = {{"id", o.id}, {"test", to_string(o.test)}};
    if (json c = conditions_json(o); !c.empty()) obs["conditions"] = c;
    obs["observable"] = to_string(o.observable);
    obs["value"] = o.value;
    obs["uncertainty"] = o.uncertainty;
    obs["role"] = to_string(o.role);
    list.push_back(obs);
  }
  j["observations"] = list;
  return j;
}

const char* to_string(Observable o) {
  switch (o) {
    case Observable::peak_load:
      return "peak_load";
    case Observable::strength:
      return "strength";
    case Observable::youngs_modulus:
      return "youngs_modulus";
    case Observable::peak_strain:
      return "peak_strain";
  }
  return "?";
}

const char* to_string(Role r) {
  return r == Role::calibration ? "calibration" : "held_out";
}

const char* to_string(Origin o) {
  switch (o) {
    case Origin::lab:
      return "lab";
    case Origin::same_resolution_model:
      return "same_resolution_model";
    case Origin::finer_model:
      return "finer_model";
  }
  return "?";
}

bool is_triaxial(TestKind test) {
  return test == TestKind::triaxial;
}

double template_platen_speed(const JobSpec& model) {
  if (!model.loading.platen_velocity_m_s)
    throw orch::RequestError("job.loading.platen_velocity",
                             "the diagnosis sets platen speeds itself (the lab's loading rates, "
                             "the error budget's half speed): give a number, not \"auto\"");
  return *model.loading.platen_velocity_m_s;
}

}  // namespace rockcal::diagnosis
