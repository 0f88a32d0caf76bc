// mfadvr query MODEL (--points FILE | X Y Z [T]) [--time T] [--derivatives 0|1|2] [--curvature]
//              [-o OUT.csv]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "app/Commands.h"
#include "core/field/Curvature.h"
#include "core/model/ModelFile.h"
#include "core/util/AtomicFile.h"
#include "core/util/Error.h"
#include "core/util/PointList.h"

#include <algorithm>
#include <map>

namespace mfadvr::app {

namespace {

// A time-varying model at points with their own times: value and gradient (and the derivative
// by time) directly from the 4-D spline; the Hessian from the 3-D model at each distinct time.
void evaluateInTime(const TimeVaryingModel& model, const std::vector<Vec3d>& points,
                    const std::vector<double>& times, std::vector<float>& values,
                    std::vector<Vec3f>& gradients, std::vector<Sym3f>& hessians,
                    std::vector<float>& rates) {
  if (hessians.empty()) {
    model.evaluate(points, times, values, gradients, rates);
    return;
  }
  std::vector<Vec3f> g4(points.size());
  model.evaluate(points, times, values, g4, rates);
  std::map<double, std::vector<size_t>> byTime;
  for (size_t i = 0; i < points.size(); ++i) byTime[times[i]].push_back(i);
  for (const auto& [t, index] : byTime) {
    const Model instant = model.at(t);
    std::vector<Vec3d> p;
    for (size_t i : index) p.push_back(points[i]);
    std::vector<float> v(p.size());
    std::vector<Vec3f> g(p.size());
    std::vector<Sym3f> h(p.size());
    instant.evaluate(p, v, g, h);
    for (size_t k = 0; k < index.size(); ++k) {
      gradients[index[k]] = g[k];
      hessians[index[k]] = h[k];
    }
  }
}

}  // namespace

Command addQueryCommand(CLI::App& app) {
  struct Options {
    std::string model, pointsFile, output;
    std::vector<double> xyz;
    std::optional<double> time;
    int derivatives = 0;
    bool curvature = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "query",
      "Evaluate a model (value, gradient, Hessian) at physical points; prints CSV (with a last "
      "column 'inside', 1 or 0, for models with a domain mask)");
  sub->add_option("model", o->model, "Model file (.mfa)")->required();
  auto* xyz = sub->add_option("x y z", o->xyz,
                              "One point, physical coordinates (time-varying models: x y z t, "
                              "or x y z with --time)")
                  ->expected(3, 4);
  auto* pts = sub->add_option("--points", o->pointsFile,
                              "Text file with one 'x y z' per line (comma or space separated; "
                              "'-' reads stdin); time-varying models: 'x y z t', or 'x y z' with "
                              "--time");
  sub->add_option("--time", o->time,
                  "Time-varying models: the time of every point (any time in the model's "
                  "range); with --derivatives 1 a column dt is added");
  xyz->excludes(pts);
  sub->add_option("--derivatives,-d", o->derivatives,
                  "0: value; 1: value and gradient; 2: value, gradient and Hessian")
      ->check(CLI::Range(0, 2))
      ->capture_default_str();
  sub->add_flag("--curvature", o->curvature,
                "Add columns k1,k2: the principal curvatures (k1 >= k2) of the level set through "
                "each point, from the exact gradient and Hessian (Kindlmann et al. 2003; positive "
                "where the surface bends around higher values: a bright blob of radius r has "
                "1/r); empty where the gradient is zero");
  sub->add_option("-o,--output", o->output, "Write the CSV to this file instead of stdout");

  return {sub, [o]() {
            const TimeVaryingModel series = loadTimeVaryingModel(o->model);
            const bool inTime = series.hasTime();
            if (!inTime && o->time)
              throw CLI::ValidationError(
                  "--time", "applies to time-varying models; " + o->model + " has no time axis");
            // Points in time: a fourth column, unless --time gives every point's time.
            const bool fourColumns = inTime && !o->time;
            std::vector<Vec3d> points;
            std::vector<double> times;
            if (!o->pointsFile.empty()) {
              std::ostringstream text;
              if (o->pointsFile == "-") {
                text << std::cin.rdbuf();
              } else {
                std::ifstream in(o->pointsFile, std::ios::binary);
                if (!in) throw Error("cannot open " + o->pointsFile);
                text << in.rdbuf();
              }
              if (fourColumns) {
                PointTimes pt = parsePointTimeList(text.str(), o->pointsFile);
                points = std::move(pt.points);
                times = std::move(pt.times);
              } else {
                points = parsePointList(text.str(), o->pointsFile);
              }
            } else if (!o->xyz.empty()) {
              if (o->xyz.size() != (fourColumns ? 4u : 3u))
                throw CLI::ValidationError(
                    "x y z", fourColumns ? o->model + " varies in time: give x y z t (or --time T)"
                                         : "give three coordinates x y z");
              for (double v : o->xyz)
                if (!std::isfinite(v))
                  throw CLI::ValidationError("x y z", "coordinates must be finite");
              points.emplace_back(o->xyz[0], o->xyz[1], o->xyz[2]);
              if (fourColumns) times.push_back(o->xyz[3]);
            } else {
              throw CLI::ValidationError("query", "give a point as X Y Z or a file with --points");
            }
            if (inTime && o->time) {
              if (!std::isfinite(*o->time))
                throw CLI::ValidationError("--time", "must be a finite number");
              times.assign(points.size(), *o->time);
            }
            const Model& model = series.first();
            std::vector<float> values(points.size());
            const bool second = o->derivatives >= 2 || o->curvature;
            std::vector<Vec3f> gradients(o->derivatives >= 1 || second ? points.size() : 0);
            std::vector<Sym3f> hessians(second ? points.size() : 0);
            std::vector<float> rates(inTime && o->derivatives >= 1 ? points.size() : 0);
            std::size_t outsideTime = 0;
            if (inTime) {
              for (double t : times) outsideTime += !series.timeAxis().contains(t);
              evaluateInTime(series, points, times, values, gradients, hessians, rates);
            } else {
              model.evaluate(points, values, gradients, hessians);
            }

            // A model with a domain mask gets a last column, inside: 1 within the mask, 0 outside
            // (where the value is the spline's extrapolation).
            const bool masked = !model.mask().empty() || model.boundary() != nullptr;
            std::size_t outside = 0, outsideMask = 0;
            std::string csv = inTime ? "x,y,z,t,value" : "x,y,z,value";
            if (o->derivatives >= 1) csv += inTime ? ",dx,dy,dz,dt" : ",dx,dy,dz";
            if (o->derivatives >= 2) csv += ",dxx,dxy,dxz,dyy,dyz,dzz";
            if (o->curvature) csv += ",k1,k2";
            if (masked) csv += ",inside";
            csv += "\n";
            char buf[64];
            auto put = [&](double v, bool last = false) {
              std::snprintf(buf, sizeof buf, "%.9g%c", v, last ? '\n' : ',');
              csv += buf;
            };
            for (size_t i = 0; i < points.size(); ++i) {
              if (!model.domain().contains(points[i])) ++outside;
              for (int a = 0; a < 3; ++a) put(points[i][a]);
              if (inTime) put(times[i]);
              const bool more = masked || o->curvature;
              put(values[i], o->derivatives == 0 && !more);
              if (o->derivatives >= 1) {
                for (int a = 0; a < 3; ++a)
                  put(gradients[i][a], o->derivatives == 1 && a == 2 && !more && !inTime);
                if (inTime) put(rates[i], o->derivatives == 1 && !more);
              }
              if (o->derivatives >= 2)
                for (int a = 0; a < 6; ++a) put(hessians[i][a], a == 5 && !more);
              if (o->curvature) {
                const PrincipalCurvatures k =
                    principalCurvatures(gradients[i].data(), hessians[i].data());
                if (std::isnan(k.k1)) {
                  csv += masked ? ",," : ",\n";
                } else {
                  put(k.k1);
                  put(k.k2, !masked);
                }
              }
              if (masked) {
                const bool in = model.inside(points[i]);
                if (!in) ++outsideMask;
                csv += in ? "1\n" : "0\n";
              }
            }
            if (outside > 0)
              std::cerr << "mfadvr query: warning: " << outside << " of " << points.size()
                        << " points lie outside the model's domain box and were clamped onto it\n";
            if (outsideTime > 0)
              std::cerr << "mfadvr query: warning: " << outsideTime << " of " << points.size()
                        << " points lie outside the model's time range (" << series.timeAxis().begin
                        << " .. " << series.timeAxis().end
                        << "): they take the value at its nearest end\n";
            if (outsideMask > 0)
              std::cerr << "mfadvr query: warning: " << outsideMask << " of " << points.size()
                        << " points lie outside the model's domain mask (inside = 0): their "
                           "values are extrapolated\n";
            if (o->output.empty())
              std::cout << csv;
            else
              writeFileAtomically(o->output, csv);
            return 0;
          }};
}

}  // namespace mfadvr::app
