// layers.open_dataset and layers.Dataset: the C++ reader (data/dataset.h)
// with its integrity check -- every sequence's content hash verified on
// first read, a dataset without hashes refused unless allow_unhashed --
// and its arrays as numpy arrays in the format's shapes (docs/format.md);
// stats.h5's normalisation statistics.
#include <pybind11/stl.h>

#include "bindings.h"
#include "layers/data/dataset.h"
#include "layers/data/stats.h"

namespace layers::python {
namespace {

using data::Dataset;

py::ssize_t n(std::size_t v) { return static_cast<py::ssize_t>(v); }

py::dict info_dict(const data::SequenceInfo& info) {
  py::dict d;
  d["id"] = info.id;
  d["shard"] = info.shard;
  d["n_frames"] = info.n_frames;
  d["motion"] = info.motion;
  d["seed"] = info.seed;
  d["tags"] = info.tags;
  d["shape"] = info.shape;
  d["body_vertices"] = info.body_vertices;
  py::list garments;
  for (const data::GarmentInfo& g : info.garments) {
    py::dict gd;
    gd["name"] = g.name;
    gd["type"] = g.type;
    gd["layer"] = g.layer;
    gd["attributes"] = g.attributes;
    gd["vertices"] = g.n_vertices;
    gd["faces"] = g.n_faces;
    garments.append(gd);
  }
  d["garments"] = garments;
  return d;
}

// A sequence's frames (the whole sequence, or a window) as a dict of
// numpy arrays; statics from `s`.
py::dict frames_dict(const data::SequenceStatic& s, data::BodyFrames body, data::WindData wind,
                     std::vector<std::vector<float>> garments, std::int64_t first, std::int64_t frames) {
  py::dict d;
  d["id"] = s.id;
  d["first_frame"] = first;
  d["n_frames"] = frames;
  const py::ssize_t t = frames, vb = s.body.n_vertices();
  py::dict b;
  b["faces"] = numpy(std::vector<std::int32_t>(s.body.faces), {s.body.n_faces(), 3});
  b["joint_names"] = s.body.joint_names;
  b["joint_parents"] = numpy(std::vector<std::int32_t>(s.body.joint_parents), {s.body.n_joints()});
  b["skin_index"] = numpy(std::vector<std::int32_t>(s.body.skin_index), {vb, 4});
  b["skin_weight"] = numpy(std::vector<float>(s.body.skin_weight), {vb, 4});
  const py::ssize_t joints = s.body.n_joints();
  b["positions"] = numpy(std::move(body.positions), {t, vb, 3});
  b["root"] = numpy(std::move(body.root), {t, 3});
  b["root_rot"] = numpy(std::move(body.root_rot), {t, 4});
  b["joints"] = numpy(std::move(body.joints), {t, joints, 3, 4});
  d["body"] = b;
  py::dict w;
  w["rotation"] = numpy(std::move(wind.rotation), {t, 4});
  w["strength"] = numpy(std::move(wind.strength), {t});
  d["wind"] = w;
  py::list gs;
  for (std::size_t k = 0; k < s.garments.size(); ++k) {
    const data::GarmentStatic& g = s.garments[k];
    py::dict gd;
    gd["name"] = g.name;
    gd["type"] = g.type;
    gd["layer"] = g.layer;
    gd["attributes"] = g.attributes;
    gd["faces"] = numpy(std::vector<std::int32_t>(g.faces), {g.n_faces(), 3});
    gd["rest"] = numpy(std::vector<float>(g.rest), {g.n_vertices(), 3});
    gd["uv"] = numpy(std::vector<float>(g.uv), {g.n_uv(), 2});
    gd["uv_faces"] = numpy(std::vector<std::int32_t>(g.uv_faces), {n(g.uv_faces.size() / 3), 3});
    gd["panel"] = numpy(std::vector<std::int32_t>(g.panel), {n(g.panel.size())});
    gd["positions"] = numpy(std::move(garments[k]), {t, g.n_vertices(), 3});
    gs.append(gd);
  }
  d["garments"] = gs;
  return d;
}

}  // namespace

void bind_data(py::module_& m) {
  py::class_<Dataset>(m, "Dataset", "A LAYERS-H5 dataset folder or shard, read as the C++ tools read it")
      .def_property_readonly("path", &Dataset::path)
      .def("ids", &Dataset::ids, "sequence ids: shard order, then order in the shard")
      .def("__len__", [](const Dataset& d) { return d.ids().size(); })
      .def("__contains__", &Dataset::contains)
      .def(
          "splits",
          [](const Dataset& d) {
            py::dict out;
            for (const std::string& name : d.splits().names()) out[py::str(name)] = d.splits().get(name);
            return out;
          },
          "splits.yaml: split or subset name -> sequence ids")
      .def(
          "info", [](const Dataset& d, const std::string& id) { return info_dict(d.info(id)); },
          "what the index knows of a sequence, without reading an array", py::arg("id"))
      .def(
          "read_sequence",
          [](const Dataset& d, const std::string& id) {
            data::SequenceData s;
            {
              py::gil_scoped_release release;
              s = d.read_sequence(id);
            }
            data::SequenceStatic st;
            st.id = s.id;
            st.n_frames = s.n_frames;
            st.body = s.body;
            std::vector<std::vector<float>> positions;
            for (data::GarmentData& g : s.garments) {
              positions.push_back(std::move(g.positions));
              st.garments.push_back(g);
            }
            return frames_dict(st, std::move(s.body), std::move(s.wind), std::move(positions), 0, s.n_frames);
          },
          "every array of a sequence (content hash verified), numpy arrays in the format's shapes", py::arg("id"))
      .def(
          "read_frames",
          [](const Dataset& d, const std::string& id, std::int64_t first, std::int64_t count) {
            data::Window w;
            std::shared_ptr<const data::SequenceStatic> st;
            {
              py::gil_scoped_release release;
              w = d.read_frames(id, first, count);
              st = d.statics(id);
            }
            return frames_dict(*st, std::move(w.body), std::move(w.wind), std::move(w.garments), w.first_frame,
                               w.n_frames);
          },
          "frames [first, first + count) of a sequence, with its static arrays", py::arg("id"), py::arg("first"),
          py::arg("count"))
      .def(
          "read_window",
          [](const Dataset& d, const std::string& id, std::int64_t start, std::int64_t history, std::int64_t horizon) {
            data::Window w;
            std::shared_ptr<const data::SequenceStatic> st;
            {
              py::gil_scoped_release release;
              w = d.read_window(id, start, history, horizon);
              st = d.statics(id);
            }
            return frames_dict(*st, std::move(w.body), std::move(w.wind), std::move(w.garments), w.first_frame,
                               w.n_frames);
          },
          "frames [start - history, start + horizon] of a sequence, as the training loader reads a window",
          py::arg("id"), py::arg("start"), py::arg("history"), py::arg("horizon"))
      .def("verify", &Dataset::verify, "verify the content hashes of these sequences now", py::arg("ids"));

  m.def(
      "read_stats",
      [](const std::string& path) {
        const data::NormStats stats = data::read_stats_verified(path);
        py::dict out;
        data::for_each_quantity(stats, [&](const char* name, const data::Moments& moments) {
          py::dict q;
          q["mean"] = numpy(std::vector<double>(moments.mean.begin(), moments.mean.end()), {3});
          q["std"] = numpy(std::vector<double>(moments.std.begin(), moments.std.end()), {3});
          q["count"] = moments.count;
          out[name] = q;
        });
        out["split"] = stats.split;
        out["n_sequences"] = stats.n_sequences;
        out["n_frames"] = stats.n_frames;
        return out;
      },
      "stats.h5: mean and std of each quantity ('garment/position', ... 'body/acceleration', root-relative; "
      "docs/format.md), as the models read them; a dataset's stats.h5 is checked against dataset.yaml's stats_hash",
      py::arg("path"));
  m.def(
      "open_dataset",
      [](const std::string& path, bool allow_unhashed) {
        data::ReaderOptions options;
        options.allow_unhashed = allow_unhashed;
        return Dataset::open(path, options);
      },
      "Open a dataset folder or shard .h5 (layers.Error / layers.InputError on a bad one). allow_unhashed: read "
      "sequences without recorded content hashes unverified (those with one are still verified).",
      py::arg("path"), py::arg("allow_unhashed") = false);
}

}  // namespace layers::python
