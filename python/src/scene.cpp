#include "scene.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "common.hpp"
#include "epicycle/transmission/helical_scene.hpp"

namespace epicycle::python {

transmission::FeComplianceOptions TableOptions(const std::optional<std::string>& cache_dir) {
  transmission::FeComplianceOptions fe;
  fe.cache_directory = cache_dir ? *cache_dir : transmission::DefaultCacheDirectory();
  return fe;
}

void PairColumns::Add(double at, const transmission::StageContact& c) {
  x.push_back(at);
  mesh.append(names(geometry::MeshName(c.planet, c.mesh)));
  kind.append(names(geometry::KindName(c.contact.kind)));
  flank.append(names(c.loaded ? "drive" : "coast"));
  tooth_a.push_back(c.contact.tooth_a);
  tooth_b.push_back(c.contact.tooth_b);
}

void PairColumns::Fill(py::dict& out, const char* x_name) {
  out[x_name] = Array(std::move(x));
  out["mesh"] = mesh;
  out["kind"] = kind;
  out["flank"] = flank;
  out["tooth_a"] = Array(std::move(tooth_a));
  out["tooth_b"] = Array(std::move(tooth_b));
}

void RunColumns::Add(const std::vector<double>& load_sharing, const std::vector<double>& factors,
                     double kg, double te_rad, double sun_x_m, double sun_y_m) {
  lsr.insert(lsr.end(), load_sharing.begin(), load_sharing.end());
  factor.insert(factor.end(), factors.begin(), factors.end());
  k_gamma.push_back(kg);
  te_urad.push_back(te_rad * 1e6);
  sun_x_um.push_back(sun_x_m * 1e6);
  sun_y_um.push_back(sun_y_m * 1e6);
}

void RunColumns::Fill(py::dict& out, int planets) {
  const auto rows = static_cast<py::ssize_t>(k_gamma.size());
  out["lsr"] = Array2(std::move(lsr), rows, planets);
  out["load_sharing_factor"] = Array2(std::move(factor), rows, planets);
  out["k_gamma"] = Array(std::move(k_gamma));
  out["te_urad"] = Array(std::move(te_urad));
  out["sun_x_um"] = Array(std::move(sun_x_um));
  out["sun_y_um"] = Array(std::move(sun_y_um));
}

void RequireStage(const transmission::Scene& scene, const char* command) {
  if (scene.kind != transmission::SceneKind::kStage)
    throw std::invalid_argument(scene.source + ": a gear-pair scene; " + command +
                                " needs a stage");
}

void RaiseRefused(const std::string& message, const std::string& text) {
  const py::object error = py::reinterpret_borrow<py::object>(PyExc_ValueError)(message);
  error.attr("scene_text") = text;
  PyErr_SetObject(PyExc_ValueError, error.ptr());
  throw py::error_already_set();
}

std::shared_ptr<Scene> Scene::Parse(const std::string& text, const std::string& source) {
  auto s = std::make_shared<Scene>();
  s->scene_ = std::make_shared<const transmission::Scene>(transmission::ParseScene(text, source));
  s->text_ = text;
  s->table_ = toml::parse(text, source);  // the reader parsed it: it is valid TOML
  return s;
}

std::shared_ptr<Scene> Scene::Load(const std::string& path) {
  // The reader's own file handling first (its messages for a directory or a missing file).
  auto parsed = std::make_shared<const transmission::Scene>(transmission::ReadScene(path));
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  auto s = std::make_shared<Scene>();
  s->scene_ = std::move(parsed);
  s->text_ = text.str();
  s->table_ = toml::parse(s->text_, path);
  return s;
}

void Scene::Assign(const Scene& other) {
  std::lock_guard<std::mutex> lock(mutex_);
  text_ = other.text_;
  table_ = other.table_;
  scene_ = other.scene_;
  rig_.reset();
  dynamics_.reset();
}

std::shared_ptr<Scene> WithStresses(const std::shared_ptr<Scene>& s) {
  if (s->scene().model.stresses) return s;
  return s->Edited([](toml::table& t) {
    if (!t["model"].is_table()) t.insert_or_assign("model", toml::table{});
    t["model"].as_table()->insert_or_assign("stresses", true);
  });
}

std::shared_ptr<const StageRig> Scene::Rig(const std::optional<std::string>& cache_dir,
                                           const char* command) const {
  const transmission::FeComplianceOptions fe = TableOptions(cache_dir);
  std::lock_guard<std::mutex> lock(mutex_);  // Assign may replace scene_ from another thread
  RequireStage(*scene_, command);
  if (!rig_ || rig_cache_ != fe.cache_directory) {
    rig_ = std::make_shared<const StageRig>(*scene_, fe);
    rig_cache_ = fe.cache_directory;
  }
  return rig_;
}

std::shared_ptr<const dynamics::StageDynamics> Scene::Dynamics(
    const std::optional<std::string>& cache_dir, const char* command) const {
  transmission::FeComplianceOptions fe = TableOptions(cache_dir);
  fe.helical_slices = true;  // the dynamic model resolves a helical stage in slices
  std::lock_guard<std::mutex> lock(mutex_);  // Assign may replace scene_ from another thread
  RequireStage(*scene_, command);
  transmission::RequireHelicalSlices(*scene_, command);
  if (!dynamics_ || dynamics_cache_ != fe.cache_directory) {
    dynamics_ = std::make_shared<const dynamics::StageDynamics>(*scene_, fe);
    dynamics_cache_ = fe.cache_directory;
  }
  return dynamics_;
}

namespace {

// A TOML value as Python: tables as dicts, arrays as lists.
py::object ToPython(const toml::node& n) {
  if (const auto* t = n.as_table()) {
    py::dict d;
    for (const auto& [k, v] : *t) d[py::str(std::string(k.str()))] = ToPython(v);
    return d;
  }
  if (const auto* a = n.as_array()) {
    py::list l;
    for (const auto& v : *a) l.append(ToPython(v));
    return l;
  }
  if (const auto* s = n.as_string()) return py::str(s->get());
  if (const auto* i = n.as_integer()) return py::int_(i->get());
  if (const auto* f = n.as_floating_point()) return py::float_(f->get());
  if (const auto* b = n.as_boolean()) return py::bool_(b->get());
  throw std::invalid_argument("a date or time value: not a scene value");
}

// A Python value as a TOML node. An integer written where the scene has a number with a
// fraction stays a floating-point number (the reader takes either for a real value).
void Insert(toml::table& t, const std::string& key, const py::handle& v, const toml::node* old) {
  if (py::isinstance<py::bool_>(v)) {
    t.insert_or_assign(key, v.cast<bool>());
  } else if (py::isinstance<py::int_>(v)) {
    if (old && old->is_floating_point())
      t.insert_or_assign(key, v.cast<double>());
    else
      t.insert_or_assign(key, v.cast<std::int64_t>());
  } else if (py::isinstance<py::float_>(v)) {
    t.insert_or_assign(key, v.cast<double>());
  } else if (py::isinstance<py::str>(v)) {
    t.insert_or_assign(key, v.cast<std::string>());
  } else if (py::isinstance<py::dict>(v)) {
    toml::table sub;
    for (const auto& [k, x] : v.cast<py::dict>()) Insert(sub, k.cast<std::string>(), x, nullptr);
    t.insert_or_assign(key, std::move(sub));
  } else if (py::isinstance<py::sequence>(v)) {
    toml::array a;
    for (const auto& x : v.cast<py::sequence>()) {
      if (py::isinstance<py::bool_>(x))
        a.push_back(x.cast<bool>());
      else if (py::isinstance<py::int_>(x))
        a.push_back(x.cast<std::int64_t>());
      else if (py::isinstance<py::str>(x))
        a.push_back(x.cast<std::string>());
      else if (py::isinstance<py::dict>(x)) {  // an array of tables (a crack's path)
        toml::table sub;
        for (const auto& [k, y] : x.cast<py::dict>())
          Insert(sub, k.cast<std::string>(), y, nullptr);
        a.push_back(std::move(sub));
      } else
        a.push_back(x.cast<double>());
    }
    t.insert_or_assign(key, std::move(a));
  } else if (py::hasattr(v, "__index__")) {  // numpy integers
    Insert(t, key, py::reinterpret_borrow<py::object>(v).attr("__index__")(), old);
  } else if (py::hasattr(v, "__float__")) {  // numpy floating-point numbers
    t.insert_or_assign(key,
                       py::reinterpret_borrow<py::object>(v).attr("__float__")().cast<double>());
  } else {
    throw std::invalid_argument(key + ": a value of Python type " +
                                py::str(v.get_type().attr("__name__")).cast<std::string>() +
                                " cannot be a scene value (numbers, strings, booleans, lists)");
  }
}

// Splits "a.b[2].c" into its parent path "a.b[2]" and last key "c".
std::pair<std::string, std::string> SplitKey(const std::string& key) {
  const auto dot = key.rfind('.');
  if (dot == std::string::npos) return {"", key};
  return {key.substr(0, dot), key.substr(dot + 1)};
}

// The table at `path` ("" the root), tables created along plain keys that are missing.
toml::table& TableAt(toml::table& root, const std::string& path, const std::string& key) {
  if (path.empty()) return root;
  if (toml::table* t = root.at_path(path).as_table()) return *t;
  if (root.at_path(path)) throw std::invalid_argument(key + ": " + path + " is not a table");
  if (path.find('[') != std::string::npos)
    throw std::invalid_argument(key + ": " + path + " is not in the scene");
  const auto [parent, last] = SplitKey(path);
  toml::table& p = TableAt(root, parent, key);
  p.insert_or_assign(last, toml::table{});
  return *p.get_as<toml::table>(last);
}

void SetKey(toml::table& root, const std::string& key, const py::handle& value) {
  const auto [path, last] = SplitKey(key);
  if (last.empty() || last.find('[') != std::string::npos)
    throw std::invalid_argument(key + ": name a key (e.g. errors.runout[0].amplitude_um)");
  if (value.is_none()) {
    if (toml::table* t = root.at_path(path).as_table()) t->erase(last);
    if (path.empty()) root.erase(last);
    return;
  }
  toml::table& t = TableAt(root, path, key);
  Insert(t, last, value, t.get(last));
}

// Appends a table to the array of tables at `key` (created if missing).
void AppendTable(toml::table& root, const std::string& key, const py::dict& fields) {
  const auto [path, last] = SplitKey(key);
  toml::table& t = TableAt(root, path, key);
  if (!t.contains(last)) t.insert_or_assign(last, toml::array{});
  toml::array* a = t.get_as<toml::array>(last);
  if (!a) throw std::invalid_argument(key + ": is not an array of tables");
  toml::table entry;
  for (const auto& [k, v] : fields) Insert(entry, k.cast<std::string>(), v, nullptr);
  a->push_back(std::move(entry));
}

// Replaces the table at `key` by `fields` (None values left out).
void SetTable(toml::table& root, const std::string& key, const py::dict& fields) {
  const auto [path, last] = SplitKey(key);
  toml::table& t = TableAt(root, path, key);
  toml::table entry;
  for (const auto& [k, v] : fields)
    if (!v.is_none()) Insert(entry, k.cast<std::string>(), v, nullptr);
  t.insert_or_assign(last, std::move(entry));
}

// Every key path of a table ("sun.cutter.type", "errors.runout[0].gear").
void KeyPaths(const toml::table& t, const std::string& prefix, py::list& out) {
  for (const auto& [k, v] : t) {
    const std::string path =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const auto* sub = v.as_table()) {
      KeyPaths(*sub, path, out);
    } else if (const auto* a = v.as_array(); a && a->is_array_of_tables()) {
      for (std::size_t i = 0; i < a->size(); ++i)
        KeyPaths(*a->get(i)->as_table(), path + "[" + std::to_string(i) + "]", out);
    } else {
      out.append(path);
    }
  }
}

using ScenePtr = std::shared_ptr<Scene>;

// Applies an edit to `s` in place (read again; unchanged if the reader refuses it).
template <typename Edit>
void EditInPlace(Scene& s, Edit&& edit) {
  s.Assign(*s.Edited(std::forward<Edit>(edit)));
}

using SceneClass = py::class_<Scene, ScenePtr>;

// Reading a scene: from a file or from text.
void BindSceneReading(SceneClass& c) {
  c.def_static("load", &Scene::Load, py::arg("path"), R"doc(
Reads a scene file.

Parameters
----------
path : str
    The TOML file.

Returns
-------
Scene
    The scene the file gives.

Raises
------
ValueError
    The reader's message (a missing file, a bad value: file, line, key, value, rule).)doc")
      .def_static("parse", &Scene::Parse, py::arg("text"), py::kw_only(),
                  py::arg("source") = "<string>", R"doc(
Reads a scene from TOML text.

Parameters
----------
text : str
    The scene's TOML.
source : str, default "<string>"
    Names the text in messages (as a file name would).

Returns
-------
Scene
    The scene the text gives.

Raises
------
ValueError
    The reader's message (line, key, value, rule).)doc");
}

// The scene's keys read and set by path, copies with changed values, the key list.
void BindSceneKeys(SceneClass& c) {
  c.def(
       "__getitem__",
       [](const Scene& s, const std::string& key) {
         const toml::node_view<const toml::node> v = s.table().at_path(key);
         if (!v) throw py::key_error(key + ": not in the scene (its default applies)");
         return ToPython(*v.node());
       },
       py::arg("key"), R"doc(
The value of a scene key as written in the scene, in the key's unit.

Parameters
----------
key : str
    A key path: "load.sun_torque_Nm" [N·m], "errors.runout[0].amplitude_um" [µm].

Returns
-------
object
    The value (a number in the key's unit, a string, a list or a dict).

Raises
------
KeyError
    The scene does not give the key (its default applies).)doc")
      .def(
          "__contains__",
          [](const Scene& s, const std::string& key) {
            return static_cast<bool>(s.table().at_path(key));
          },
          py::arg("key"), R"doc(
Whether the scene gives a key (else its default applies).

Parameters
----------
key : str
    A key path ("supports.sun").

Returns
-------
bool)doc")
      .def(
          "get",
          [](const Scene& s, const std::string& key, py::object fallback) {
            const toml::node_view<const toml::node> v = s.table().at_path(key);
            return v ? ToPython(*v.node()) : fallback;
          },
          py::arg("key"), py::arg("default") = py::none(),
          R"doc(
The value of a scene key in its unit, or `default` where the scene does not give it.

Parameters
----------
key : str
    A key path ("load.sun_torque_Nm").
default : object, default None
    Returned when the scene does not give the key.

Returns
-------
object)doc")
      .def(
          "set",
          [](Scene& s, const std::string& key, py::object value) {
            EditInPlace(s, [&](toml::table& t) { SetKey(t, key, value); });
          },
          py::arg("key"), py::arg("value"), R"doc(
Sets a scene key in place: scene.set("supports.sun", "floating"),
scene.set("load.sun_torque_Nm", -700.0). Tables are created as needed.

Parameters
----------
key : str
    A key path.
value : object
    The value in the key's unit (None removes the key: its default applies).

Raises
------
ValueError
    The scene reader's message for a bad value or an unknown key (the scene unchanged).)doc")
      .def(
          "with_values",
          [](const Scene& s, const py::dict& values) {
            return s.Edited([&](toml::table& t) {
              for (const auto& [k, v] : values) SetKey(t, k.cast<std::string>(), v);
            });
          },
          py::arg("values"), R"doc(
A copy with several keys set; this scene is unchanged.

Parameters
----------
values : dict
    {key path: value in the key's unit}.

Returns
-------
Scene

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc")
      .def(
          "copy", [](const Scene& s) { return s.Edited([](toml::table&) {}); },
          R"doc(
A copy of the scene (its TOML as written by the editor).

Returns
-------
Scene)doc")
      .def(
          "keys",
          [](const Scene& s) {
            py::list out;
            KeyPaths(s.table(), "", out);
            return out;
          },
          R"doc(
Every key the scene gives.

Returns
-------
list of str
    Key paths ("sun.cutter.type", "errors.runout[0].gear").)doc");
}

// Manufacturing errors added to a gear: pin-hole positions, run-out, tooth thickness.
void BindSceneErrors(SceneClass& c) {
  c.def(
       "add_pin",
       [](Scene& s, const std::string& gear, double radial_um, double tangential_um) {
         py::dict f;
         f["gear"] = gear;
         f["radial_um"] = radial_um;
         f["tangential_um"] = tangential_um;
         EditInPlace(s, [&](toml::table& t) { AppendTable(t, "errors.pin", f); });
       },
       py::arg("gear"), py::kw_only(), py::arg("radial_um") = 0.0, py::arg("tangential_um") = 0.0,
       R"doc(
Adds a planet pin-hole position error ([[errors.pin]]).

Parameters
----------
gear : str
    "planet1".."planetN".
radial_um : float, default 0
    Radial error [µm] (outward +).
tangential_um : float, default 0
    Tangential error [µm] (counter-clockwise +).

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc")
      .def(
          "add_runout",
          [](Scene& s, const std::string& gear, double amplitude_um, double phase_deg) {
            py::dict f;
            f["gear"] = gear;
            f["amplitude_um"] = amplitude_um;
            f["phase_deg"] = phase_deg;
            EditInPlace(s, [&](toml::table& t) { AppendTable(t, "errors.runout", f); });
          },
          py::arg("gear"), py::arg("amplitude_um"), py::kw_only(), py::arg("phase_deg") = 0.0,
          R"doc(
Adds a run-out ([[errors.runout]]): the geometric centre off the rotation centre.

Parameters
----------
gear : str
    "sun", "ring", "planet1".."planetN" (docs/scenes.md).
amplitude_um : float
    The offset [µm].
phase_deg : float, default 0
    Its direction in the gear's frame [deg].

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc")
      .def(
          "add_thickness",
          [](Scene& s, const std::string& gear, double error_um) {
            py::dict f;
            f["gear"] = gear;
            f["error_um"] = error_um;
            EditInPlace(s, [&](toml::table& t) { AppendTable(t, "errors.thickness", f); });
          },
          py::arg("gear"), py::arg("error_um"),
          R"doc(
Adds a tooth-thickness error ([[errors.thickness]]), normal to the flank, both flanks.

Parameters
----------
gear : str
    "sun", "ring", "planet1".."planetN" (docs/scenes.md).
error_um : float
    The error [µm] (+ thicker).

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc");
}

// Damage added to a tooth: a pit (spall) and a root crack.
void BindSceneDamage(SceneClass& c) {
  c.def(
       "add_pit",
       [](Scene& s, const std::string& gear, int tooth, const std::string& flank,
          py::object roll_deg, py::object radius_mm, double width_fraction, double depth_um) {
         if (roll_deg.is_none() == radius_mm.is_none())
           throw py::value_error(
               "add_pit: give the region as roll_deg=(from, to) [deg] or radius_mm=(from, to) "
               "[mm], one of the two");
         py::dict f;
         f["gear"] = gear;
         f["tooth"] = tooth;
         f["flank"] = flank;
         const bool roll = !roll_deg.is_none();
         const auto range = (roll ? roll_deg : radius_mm).cast<std::pair<double, double>>();
         f[roll ? "roll_from_deg" : "radius_from_mm"] = range.first;
         f[roll ? "roll_to_deg" : "radius_to_mm"] = range.second;
         f["width_fraction"] = width_fraction;
         f["depth_um"] = depth_um;
         EditInPlace(s, [&](toml::table& t) { AppendTable(t, "damage.pit", f); });
       },
       py::arg("gear"), py::arg("tooth"), py::arg("flank"), py::kw_only(),
       py::arg("roll_deg") = py::none(), py::arg("radius_mm") = py::none(),
       py::arg("width_fraction") = 1.0, py::arg("depth_um"),
       R"doc(
Adds a pit or spall ([[damage.pit]], docs/model.md §9 "Pitting and spalls") on one flank of one
tooth; the region by roll angle or by radius, one of the two.

Parameters
----------
gear : str
    "sun", "ring", "planet1".."planetN" (docs/scenes.md).
tooth : int
    The tooth (body frame, 0..z-1).
flank : str
    "+" or "-".
roll_deg : tuple of float or None, default None
    (from, to) involute roll angle [deg].
radius_mm : tuple of float or None, default None
    (from, to) radius [mm].
width_fraction : float, default 1
    The share of the face width covered [-].
depth_um : float
    The depth [µm].

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc")
      .def(
          "add_crack",
          [](Scene& s, const std::string& gear, int tooth, const std::string& side,
             py::object start, py::object start_arc_mm, py::object depth_mm, py::object angle_deg,
             py::object path_mm_deg) {
            py::dict f;
            f["gear"] = gear;
            f["tooth"] = tooth;
            f["side"] = side;
            if (!start.is_none()) f["start"] = start;
            if (!start_arc_mm.is_none()) f["start_arc_mm"] = start_arc_mm;
            if (!depth_mm.is_none()) f["depth_mm"] = depth_mm;
            if (!angle_deg.is_none()) f["angle_deg"] = angle_deg;
            if (!path_mm_deg.is_none()) {
              py::list path;
              for (const auto& segment : path_mm_deg.cast<py::sequence>()) {
                const auto [length, angle] = segment.cast<std::pair<double, double>>();
                py::dict g;
                g["length_mm"] = length;
                g["angle_deg"] = angle;
                path.append(g);
              }
              f["path"] = path;
            }
            EditInPlace(s, [&](toml::table& t) { AppendTable(t, "damage.crack", f); });
          },
          py::arg("gear"), py::arg("tooth"), py::arg("side"), py::kw_only(),
          py::arg("start") = py::none(), py::arg("start_arc_mm") = py::none(),
          py::arg("depth_mm") = py::none(), py::arg("angle_deg") = py::none(),
          py::arg("path_mm_deg") = py::none(),
          R"doc(
Adds a root crack ([[damage.crack]], docs/model.md §9 "Root crack"; one per gear). The crack is
open; it needs gmsh, and no root stresses can be asked with it.

Parameters
----------
gear : str
    "sun", "ring", "planet1".."planetN" (docs/scenes.md).
tooth : int
    The cracked tooth (body frame, 0..z-1).
side : str
    The fillet of flank side "+" or "-".
start : str or None, default None
    "largest_tension" (the default) or "iso_30deg".
start_arc_mm : float or None, default None
    The start at this arc length [mm] along the fillet from the space centre line instead.
depth_mm : float or None, default None
    A straight crack's depth [mm].
angle_deg : float or None, default None
    A straight crack's angle to the tooth centre line [deg] (below 90 toward the root).
path_mm_deg : list of (float, float) or None, default None
    A polyline instead: [(length_mm [mm], angle_deg [deg]), ...].

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc");
}

// Flank changes of a gear: pitch deviations and tip or root relief.
void BindSceneFlanks(SceneClass& c) {
  c.def(
       "set_pitch",
       [](Scene& s, const std::string& gear, py::object single_um, py::object cumulative_um,
          py::object iso1328_grade, py::object seed) {
         py::dict f;
         f["single_um"] = single_um;
         f["cumulative_um"] = cumulative_um;
         f["iso1328_grade"] = iso1328_grade;
         f["seed"] = seed;
         EditInPlace(s, [&](toml::table& t) { SetTable(t, gear + ".pitch", f); });
       },
       py::arg("gear"), py::kw_only(), py::arg("single_um") = py::none(),
       py::arg("cumulative_um") = py::none(), py::arg("iso1328_grade") = py::none(),
       py::arg("seed") = py::none(), R"doc(
Sets a gear's pitch deviations ([<gear>.pitch]): exactly one of single_um, cumulative_um or
iso1328_grade.

Parameters
----------
gear : str
    "sun", "planet", "ring", "gear1", "gear2".
single_um : list of float or None, default None
    z single pitch deviations [µm], summing to 0.
cumulative_um : list of float or None, default None
    z cumulative pitch deviations [µm].
iso1328_grade : int or None, default None
    ISO 1328-1 class 1..11 (with seed).
seed : int or None, default None
    The sampling's seed, >= 0.

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc")
      .def(
          "set_relief",
          [](Scene& s, const std::string& gear, const py::kwargs& keys) {
            py::dict f;
            for (const auto& [k, v] : keys) f[k] = v;
            EditInPlace(s, [&](toml::table& t) { SetTable(t, gear + ".modification", f); });
          },
          py::arg("gear"), R"doc(
Sets a gear's profile relief ([<gear>.modification]); replaces the gear's previous relief.

Parameters
----------
gear : str
    "sun", "planet", "ring", "gear1", "gear2".
**kwargs
    tip_relief_um [µm], tip_relief_start_mm [mm] or tip_relief_start_roll_deg [deg],
    tip_relief_shape ("linear", "parabolic"), and the same root_relief_* keys.

Raises
------
ValueError
    The scene reader's message for a bad value (the scene unchanged).)doc");
}

// What the scene is: its text, names, counts, load, hash and warnings.
void BindSceneProperties(SceneClass& c) {
  c.def_property_readonly("text", &Scene::text, "The scene's TOML text.")
      .def_property_readonly(
          "source", [](const Scene& s) { return s.scene().source; },
          "The file name (or source) used in messages.")
      .def_property_readonly(
          "name", [](const Scene& s) { return s.scene().name; }, "The scene's name ([scene] name).")
      .def_property_readonly(
          "kind",
          [](const Scene& s) {
            return s.scene().kind == transmission::SceneKind::kStage ? "stage" : "pair";
          },
          "\"stage\" or \"pair\".")
      .def_property_readonly(
          "planets", [](const Scene& s) { return s.scene().stage.planets; },
          "Number of planets n [-] (stage scenes).")
      .def_property_readonly(
          "sun_support",
          [](const Scene& s) { return transmission::SunSupportName(s.scene().supports.sun); },
          "\"fixed\", \"floating\" or \"elastic\" (the key supports.sun).")
      .def_property_readonly(
          "sun_torque_Nm", [](const Scene& s) { return s.scene().loads.sun_torque; },
          "Input torque on the sun [N·m] (ccw +).")
      .def_property_readonly(
          "hash", [](const Scene& s) { return s.scene().hash; },
          "Content hash of the scene text (the provenance of results).")
      .def_property_readonly(
          "warnings", [](const Scene& s) { return s.scene().warnings; },
          "Legal values outside the model's validity, one message each.")
      .def("__repr__", [](const Scene& s) {
        return "<epicycle.Scene '" + s.scene().name + "' from " + s.scene().source + ">";
      });
}

}  // namespace

void BindScene(py::module_& m) {
  SceneClass c(m, "Scene", R"doc(
A scene: one planetary stage (or gear pair) read from TOML (docs/scenes.md). Keys name their
units (module_mm, torque_Nm, runout_um). Every change goes through the scene's keys and is read
again by the scene reader, so a bad value raises ValueError with the reader's message (file, line,
key, value, rule) and leaves the scene unchanged.)doc");
  BindSceneReading(c);
  BindSceneKeys(c);
  BindSceneErrors(c);
  BindSceneDamage(c);
  BindSceneFlanks(c);
  BindSceneProperties(c);
}

}  // namespace epicycle::python
