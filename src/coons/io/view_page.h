// The page of `coons view` (docs/formats.md, "`coons view`"): one self-contained HTML file with
// three.js inlined, the surface shaded with reflection lines, its control net, one slider per
// parameter family and the energy curves with the current value and the optima marked. The nets
// and surfaces of the sliders' values are computed beforehand (view_data.h) and embedded as JSON:
// per frame the net (#net points by 3) and the sampled surface (#samples by 3, with unit
// normals); per slider the net's edges and the surface's triangles, shared by its frames. A value
// between the frames (#alpha=A, setValue) is solved by the page itself where the slider carries
// its ring (the one-ring α family, ViewSlider::ring) or its system (ViewSystem: a triangle's c, a
// B-spline boundary's α, the C1 weight, up to ViewSystem::kMaxFree free points), else shown by the
// nearest frame.
// The page sets on document.body: data-PARAMETER (the value shown, e.g. data-alpha; data-mu with
// it where the frame has a μ), data-ready="1"
// once drawn, data-net-hash (a hash of the drawn net's coordinates), data-error (the first script
// error); window.coonsView.setValue(parameter, v) and setAlpha(v) move a slider, exact(parameter)
// says whether values between the frames are solved, net() gives the net shown, selfCheck(parameter)
// the page's own solve at every frame's value beside that frame (the browser test).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace coons {

struct ViewFrame {
  double parameter = 0;
  bool ok = true;            //!< false: the solve failed; the page shows no surface for it
  std::optional<double> mu;  //!< the μ of this α where it has one (m = n, α ∈ [−1/4, 0)), shown beside it
  Eigen::MatrixX3d net;      //!< control points, in the order of the slider's net_edges indices
  Eigen::MatrixX3d points;   //!< surface samples
  Eigen::MatrixX3d normals;  //!< unit normals of the samples (a non-finite one is written as 0)
};

struct ViewCurve {
  std::string name;                //!< "thin_plate", "e3", ...
  std::vector<double> values;      //!< one per frame (non-finite: not drawn)
  std::optional<double> optimum;   //!< the parameter of its minimum (the search's, not the grid's)
  std::string status = "success";  //!< the search's status (to_string(SearchStatus))
};

struct ViewMark {  //!< a named parameter value drawn on the curves (e.g. "Coons" at −1/4)
  std::string name;
  double parameter = 0;
};

//! A family whose net the page solves itself at any value t of its slider: the free points x of
//! (A0 + t·A1) x = B0 + t·B1 (#free square, #free by 3, in the coordinates of `net`), the other
//! points those of `net`, then the surface sampled as the frames are. Written in full precision.
//! The page solves it densely (LU with partial pivoting), so a slider carries one only up to
//! kMaxFree free points; beyond, it shows the nearest frame.
struct ViewSystem {
  static constexpr int kMaxFree = 600;
  enum class Sampler {
    kBezier,    //!< the tensor Bézier surface of a (m+1)×(n+1) net, as sample_grid
    kTriangle,  //!< the triangular Bézier surface of degree n, as tri::sample_tri_surface
    kTensor,    //!< Σ basis_u(a, i)·basis_v(b, j)·net(i, j): a B-spline surface's samples
  };
  Sampler sampler = Sampler::kBezier;
  int m = 0, n = 0;       //!< the Bézier degrees (kBezier), the triangle's degree (kTriangle, in n)
  int samples = 0;        //!< samples per side: the frames' k
  std::vector<int> free;  //!< the row of ViewFrame::net of each unknown
  Eigen::SparseMatrix<double> A0, A1;
  Eigen::MatrixX3d B0, B1;
  Eigen::MatrixX3d net;  //!< every point of the net (the free ones are solved for)
  //! kTensor: the basis functions (k × #u, k × #v) at the samples and their derivatives.
  Eigen::MatrixXd basis_u, dbasis_u, basis_v, dbasis_v;
};

struct ViewSlider {
  std::string parameter;  //!< "alpha" or "weight": the body attribute is data-PARAMETER
  std::string symbol;     //!< the parameter's symbol on the page ("α", "w", "c")
  std::string label;      //!< shown beside the slider
  double lower = 0, upper = 1;
  double initial = 0;
  std::vector<std::array<int, 2>> net_edges;  //!< index pairs into ViewFrame::net
  std::vector<std::array<int, 3>> faces;      //!< index triples into ViewFrame::points
  std::vector<ViewFrame> frames;              //!< increasing parameter
  std::vector<ViewCurve> curves;
  std::vector<ViewMark> marks;
  //! The 3×3 α family with one data ring on a rectangle of degree (ring_m, ring_n) ≥ (2, 2): the
  //! page then solves the net of a value between the frames itself (in the sine basis, as the
  //! `fast` backend does) and samples its Bézier surface, so that #alpha=A shows α = A exactly.
  //! `ring` holds the net's points (#(ring_m+1)(ring_n+1) by 3; only the outer ring is read),
  //! written in full precision. Empty (ring_m = 0) for the other sliders: they show the nearest frame.
  Eigen::MatrixX3d ring;
  int ring_m = 0, ring_n = 0;
  //! The other families (a triangle's c, a B-spline boundary's α, the C1 weight): their system,
  //! solved by the page between the frames as the ring is; none beyond ViewSystem::kMaxFree.
  std::optional<ViewSystem> system;
};

struct ViewPage {
  std::string title;
  std::string subtitle;             //!< e.g. "degree (6, 6), 101 values of α"
  std::string generator;            //!< "coons VERSION"
  std::vector<ViewSlider> sliders;  //!< at least one; the first one is shown first

  //! Checks the sizes (frames, faces and edges in range, curves of one value per frame).
  bool is_valid(std::string* why) const;
};

//! The edges of a rows × cols grid of points numbered r·cols + c (rows, cols ≥ 1).
std::vector<std::array<int, 2>> grid_edges(int rows, int cols);
//! Two triangles per cell of a k × k grid (k ≥ 2).
std::vector<std::array<int, 3>> grid_faces(int k);

//! The embedded data: one JSON object (coordinates with 5 significant digits, parameters and
//! curve values in shortest round-trip form). Safe inside a <script> element ("</" is escaped).
std::string view_page_json(const ViewPage& page);

//! The whole HTML file; `three_js` is the text of three.min.js (revision 111 or later).
//! Precondition: page.is_valid().
std::string view_page_html(const ViewPage& page, std::string_view three_js);

//! The page's own script and style (view_page_assets.cpp).
std::string_view view_page_script();
std::string_view view_page_style();

}  // namespace coons
