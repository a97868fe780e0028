// Tests of include/tumble/orientation/rotation_vector.hpp: the rotation vector v = phi n.
//
// Every expected value comes from an independent source: Eigen::AngleAxis for R and the
// quaternion, central finite differences in long double for R^T Rdot and Gdot vdot, Eigen's
// AutoDiffScalar, the identities G G^-1 = I and G vddot = alpha - Gdot vdot (Eq. 1.10), and a
// table of 50-digit references computed with mpmath (below) for the accuracy of the Taylor
// branches and the closed forms around their thresholds. Reference chapter:
// Chapter 1, "Rigid body", Eqs. (1.1), (1.5), (1.10).

#include "tumble/orientation/rotation_vector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "support/axis_angle_sample.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/numeric.hpp"
#include "support/random.hpp"
#include "tumble/core/math.hpp"

namespace {

using P = tumble::RotationVector;
using tumble::Matrix3;
using tumble::Vector3;
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
using LD = long double;
using tumble::test::ad_derivative;
using tumble::test::ad_derivatives;
using tumble::test::along;
using tumble::test::eps;
using tumble::test::five_point_derivative;
using tumble::test::kFivePointTol;
using tumble::test::rel_err;
using Vector3ld = Vector3<LD>;
using Matrix3ld = Matrix3<LD>;

const LD kPi = std::acos(-1.0L);

/// The condition number of G = I - a S(v) + b S(v)^2: its singular values are 1 (along v) and
/// sin(phi/2) / (phi/2) (twice, across v), so cond(G) = (phi/2) / |sin(phi/2)|.
LD condition(LD phi) { return phi > 0 ? (phi / 2) / std::abs(std::sin(phi / 2)) : 1.0L; }

/// The rotation vector v = phi n, and the angle of a given v.
struct RotationVectorDefinition {
  static LD magnitude(LD phi) { return phi; }
  static LD angle(LD norm) { return norm; }
};
template <class S> using Sample = tumble::test::AxisAngleSample<S, RotationVectorDefinition>;

/// Random attitudes with phi up to phi_max, plus fixed ones at and near zero.
template <class S> std::vector<Sample<S>> samples(LD phi_max, int count) {
  return tumble::test::axis_angle_samples<Sample<S>>(2718,
                                                     {{0.0L, Vector3ld(1, 0, 0)},
                                                      {1e-8L, Vector3ld(1, 2, -2)},
                                                      {1e-3L, Vector3ld(0, 1, 0)},
                                                      {phi_max, Vector3ld(1, -2, 3)}},
                                                     phi_max, count);
}

// ---- high-precision references ------------------------------------------------------------------
// For v = t (0.25, -0.375, 0.75) (phi = 0.875 t; exact in float), vdot = (0.5, 0.25, -0.125) and
// omega = (-0.25, 0.5, 0.375), each row holds R (row-major), G vdot, Gdot vdot, G^-1 omega and
// the quaternion (e0, e1, e2, e3), computed with mpmath at 80 digits (printed to 22) from
// definitions that share no formula with the code:
//   R(v) = mp.expm(S(v));  vex(m) = (m32 - m23, m13 - m31, m21 - m12) / 2
//   omega(v, vd) = vex(R(v)^T (R(v + h vd) - R(v - h vd)) / (2 h)),  h = 1e-25
//   G(v) = [omega(v, e1), omega(v, e2), omega(v, e3)];  G vdot = G(v) * vd
//   Gdot vdot = (G(v + h vd) vd - G(v - h vd) vd) / (2 h),  h = 1e-20
//   G^-1 omega = mp.lu_solve(G(v), w);  q = (cos(phi/2), sin(phi/2) v / phi)
// (checked against the closed forms of G and Gdot vdot in mpmath: they agree to 1e-36). The
// rows straddle every series threshold (phi = 1.19 .. 2) and reach 2 pi - 0.16.
struct Reference {
  LD t;
  LD r[22];
};
// clang-format off
const Reference kReferences[] = {
    {0x1p-27L,
     {9.999999999999999804844e-1L, -5.587935450294956268133e-9L, -2.793967718642265099154e-9L,
      5.587935445090785840203e-9L, 9.999999999999999826528e-1L, -1.862645157037212659952e-9L,
      2.793967729050605955014e-9L, 1.862645141424701376160e-9L, 9.999999999999999943621e-1L,
      5.000000005238689445349e-1L, 2.499999984866008146958e-1L, -1.250000009313225741637e-1L,
      1.406685139148704817952e-10L, -1.333925563774847100357e-10L, 2.958889429045125079616e-10L,
      -2.500000019208528092229e-1L, 4.999999989522621017325e-1L, 3.750000001164153206072e-1L,
      9.999999999999999946874e-1L, 9.313225746154785139758e-10L, -1.396983861923217770964e-9L,
      2.793967723846435541927e-9L}},
    {0x1p-14L,
     {9.999999986903276297583e-1L, -4.577654178872232761806e-5L, -2.288783433690441656501e-5L,
      4.577619254275692982284e-5L, 9.999999988358467820073e-1L, -1.525931292419463959964e-5L,
      2.288853282883521215544e-5L, 1.525826518629844621399e-5L, 9.999999996216502041524e-1L,
      5.000042912870402492606e-1L, 2.499876021296009396785e-1L, -1.250076293642129465810e-1L,
      1.152359193882951788950e-6L, -1.092759703053522324396e-6L, 2.423917369893369141923e-6L,
      -2.500157355643750634015e-1L, 4.999914168086737239054e-1L, 3.750009535924618830865e-1L,
      9.999999996434780769262e-1L, 7.629394530343317863255e-6L, -1.144409179551497679488e-5L,
      2.288818359102995358977e-5L}},
    {0x1p-7L,
     {9.999785424114405549420e-1L, -5.862190377108395549934e-3L, -2.923942659034382755642e-3L,
      5.856468353492543534474e-3L, 9.999809265879471599485e-1L, -1.961692823857267870591e-3L,
      2.935386706266086786562e-3L, 1.944526753009711824211e-3L, 9.999938011410828269833e-1L,
      5.005452611607471699672e-1L, 2.484113834547124448573e-1L, -1.259760619928928342271e-1L,
      1.475457884053997489107e-4L, -1.400011326870011986469e-4L, 3.101818709847515252229e-4L,
      -2.520131468764996413495e-1L, 4.988993604962296818882e-1L, 3.751207292069480547272e-1L,
      9.999941587504987198661e-1L, 9.765605985508541787066e-4L, -1.464840897826281268060e-3L,
      2.929681795652562536120e-3L}},
    {0.125L,
     {9.945123099310083860158e-1L, -9.429488361661805203378e-2L, -4.531821178531182135550e-2L,
      9.283149959822028830467e-2L, 9.951220532720074542363e-1L, -3.338280656340303565008e-2L,
      4.824497982210734881373e-2L, 2.899265450820974446273e-2L, 9.984146673134024226268e-1L,
      5.077433269107542208651e-1L, 2.241975199596917860981e-1L, -1.404823489904055139060e-1L,
      2.369239613263419080187e-3L, -2.269993379381923341173e-3L, 4.940994702146605885938e-3L,
      -2.819671113517548281749e-1L, 4.819080599809262283464e-1L, 3.766097337743813902315e-1L,
      9.985050113189740850574e-1L, 1.561721282430470332054e-2L, -2.342581923645705498081e-2L,
      4.685163847291410996161e-2L}},
    {0.5L,
     {9.135023623299416108878e-1L, -3.746840959593832226678e-1L, -1.585095020896721482965e-1L,
      3.516180592473676522379e-1L, 9.231132109599480985670e-1L, -1.556494142691485014625e-1L,
      2.046415755137032891564e-1L, 8.645130413310179017275e-2L, 9.750117935619831320343e-1L,
      5.181556525584219219060e-1L, 1.431151516213358452863e-1L, -1.844943083754727179922e-1L,
      9.479542065849467487140e-3L, -9.410468916263171726029e-3L, 1.935251090264122624499e-2L,
      -3.747425585670834621928e-1L, 4.214417581426554839505e-1L, 3.773017319270222293728e-1L,
      9.761694738686352767240e-1L, 6.200273745571718764588e-2L, -9.300410618357578146882e-2L,
      1.860082123671515629376e-1L}},
    {1L,
     {6.703032370887679768581e-1L, -7.018539988761874465819e-1L, -2.410280784676830489103e-1L,
      6.139348620998589070774e-1L, 7.069362107455715349849e-1L, -3.511768486605005348667e-1L,
      4.168663520203401279193e-1L, 8.741943833151491635310e-2L, 9.047542684923107488701e-1L,
      5.020293655739359558979e-1L, 3.256609148111807327541e-2L, -2.343934094507529486616e-1L,
      1.846613581442442883146e-2L, -1.940939995616930287814e-2L, 3.703274563231838581642e-2L,
      -4.909951575534394913508e-1L, 3.260700669195566397338e-1L, 3.683667526442581503172e-1L,
      9.058136834259364207445e-1L, 1.210503592011251458176e-1L, -1.815755388016877187264e-1L,
      3.631510776033754374529e-1L}},
    {1.5L,
     {3.162146838774801307374e-1L, -9.198798526511571320686e-1L, -2.320114876180719429468e-1L,
      7.375371016851518335986e-1L, 3.921908301133156717666e-1L, -5.497502855050594419829e-1L,
      5.966969895500825398868e-1L, 2.722032607043546572831e-3L, 8.024620197868275933241e-1L,
      4.541113513158904372125e-1L, -7.116417988409090612634e-2L, -2.702858737140089321340e-1L,
      2.615601357065680183820e-2L, -2.941734408098013982531e-2L, 5.219455463491445517115e-2L,
      -5.982468119887314655029e-1L, 2.128729757031740787410e-1L, 3.475187585144975278714e-1L,
      7.922858596771785431415e-1L, 1.743285934502261060782e-1L, -2.614928901753391591173e-1L,
      5.229857803506783182346e-1L}},
    {1.75L,
     {1.179412426477236817701e-1L, -9.740805308185477271833e-1L, -1.930206796251817575150e-1L,
      7.388648621912740423220e-1L, 2.159477712424210504623e-1L, -6.383144017758808222095e-1L,
      6.634520168797291272377e-1L, -6.733260410594023237440e-2L, 7.451830256537868414002e-1L,
      4.199912245273385189533e-1L, -1.174455374463576310358e-1L, -2.820531768989583218357e-1L,
      2.930209279231086925048e-2L, -3.422316397530455223134e-2L, 5.863276802294913550777e-2L,
      -6.482249046238415573973e-1L, 1.490504851374117117083e-1L, 3.322668774433197083199e-1L,
      7.209493809456964180438e-1L, 1.979964934989479743662e-1L, -2.969947402484219615493e-1L,
      5.939894804968439230987e-1L}},
    {2L,
     {-8.206270416790089933103e-2L, -9.876915531143326997760e-1L, -1.331582085011993834443e-1L,
      6.991414986695591266211e-1L, 3.816648518408808948353e-2L, -7.139639236311423307986e-1L,
      7.102583173907465297542e-1L, -1.516862397031783886662e-1L, 6.874041076848286290821e-1L,
      3.804120038895060190020e-1L, -1.586268085962813223888e-1L, -2.894507389279760008617e-1L,
      3.189509004990601249745e-2L, -3.878679138466275680713e-2L, 6.423781284991349808961e-2L,
      -6.955616055488145319847e-1L, 7.999700314569152412657e-2L, 3.135190367557839393915e-1L,
      6.409968581633251303566e-1L, 2.192981434960077256099e-1L, -3.289472152440115884148e-1L,
      6.578944304880231768296e-1L}},
    {2.25L,
     {-2.742647580074619687385e-1L, -9.600642038935234665323e-1L, -5.527718261094107702001e-2L,
      6.202602684248669415354e-1L, -1.326797848955217499898e-1L, -7.730933152560498555067e-1L,
      7.348850535482541270139e-1L, -2.463184911499197194841e-1L, 6.318790699089554312533e-1L,
      3.365379651508912855400e-1L, -1.938792964230437171219e-1L, -2.924523032618189537410e-1L,
      3.388956329734894349618e-2L, -4.302810622420726465933e-2L, 6.897864275031363378958e-2L,
      -7.400485504376293997819e-1L, 5.299886650991556430742e-3L, 2.909994601380389114760e-1L,
      5.533838014899721729397e-1L, 2.379789680723405597218e-1L, -3.569684521085108395826e-1L,
      7.139369042170216791653e-1L}},
    {2.5L,
     {-4.495043667379082674347e-1L, -8.925152316912136939705e-1L, 3.691050640036257549300e-2L,
      5.059807338944381559879e-1L, -2.884483259892517932753e-1L, -8.128844076261052819669e-1L,
      7.361584891931885004722e-1L, -3.467190857642213319808e-1L, 5.812542940534931671855e-1L,
      2.896291772162251630216e-1L, -2.225675490834870587030e-1L, -2.911601669471519170254e-1L,
      3.525760903361320024391e-2L, -4.687180255708647019821e-2L, 7.284211053391380137253e-2L,
      -7.814252768747868820466e-1L, -7.555668207150048849602e-2L, 2.643634179225120497675e-1L,
      4.591572718923041042539e-1L, 2.538157132635065792683e-1L, -3.807235698952598689024e-1L,
      7.614471397905197378048e-1L}},
    {3.5L,
     {-8.338636996459829741567e-1L, -3.122382028791317486416e-1L, 4.551687984424284503981e-1L,
      -1.767921170264637111336e-1L, -6.301010663519848659171e-1L, -7.561198275005045292474e-1L,
      5.228918413687624691521e-1L, -7.109711322162818500780e-1L, 4.702171534356049185769e-1L,
      9.781019076399994043365e-2L, -2.664607697650141712963e-1L, -2.491671151371737324594e-1L,
      3.453920866348991320286e-2L, -5.705618213486046925601e-2L, 7.984044229887573946622e-2L,
      -9.079046271425412010478e-1L, -4.762728217373203665523e-1L, 1.061651315121868837398e-1L,
      3.953601977196578681631e-2L, 2.854908988349702949176e-1L, -4.282363482524554423763e-1L,
      8.564726965049108847527e-1L}},
    {6L,
     {5.519152342016904233027e-1L, 6.764849303544471300572e-1L, 4.876040537766600905944e-1L,
      -7.959742012339963505098e-1L, 6.017024304015025984913e-1L, 6.617594894541674941557e-2L,
      -2.486255120175616496891e-1L, -4.246437615840644107734e-1L, 8.705532898804883445097e-1L,
      -9.061419908904797727212e-2L, -4.842993662617682715005e-2L, -7.734356861673908781765e-2L,
      9.717223081949196639540e-3L, -4.277330941458252757791e-2L, 5.890130151516473943039e-2L,
      -3.342411732435952518613e-1L, -3.240338558870527050235L, -1.467088888354065107831L,
      -8.695071814659844093678e-1L, 1.411200853171683356584e-1L, -2.116801279757525034876e-1L,
      4.233602559515050069752e-1L}},
    {7L,
     {9.885339736419947995642e-1L, 1.334938516354361766864e-1L, 7.056893460371982182179e-2L,
      -1.365514586642375634693e-1L, 9.898079765706620440571e-1L, 4.042114117341020985164e-2L,
      -6.445372054611704825605e-2L, -4.959396225981437020025e-2L, 9.966875923854651643186e-1L,
      -3.346473241045481812938e-2L, 2.402349658880833128893e-2L, -6.016667423544422831241e-2L,
      3.384342029973958187849e-3L, -2.927504511646428593907e-2L, 4.734496491341364195897e-2L,
      8.259707635431540995539L, -2.091092222899187530489e+1L, -1.316703032630645131763e+1L,
      -9.968738062811814607485e-1L, 2.257434764211133958466e-2L, -3.386152146316700937699e-2L,
      6.772304292633401875399e-2L}},
};
// clang-format on

// The coefficient functions (sin phi / phi, a, b, d, c1, c2, cos(phi/2), sin(phi/2) / phi) at
// exact dyadic x = phi^2, computed with mpmath at 150 digits from the closed forms of the header
// comment (at small x they cancel ~x^2 of the digits; the rows with x <= 1 agree with the exact
// 30-term series to the 22 printed digits). The rows straddle every threshold: x = 4 (the cap of
// the half-angle series), 12.25 (the cap of the coefficient series), 2.5637 (d in double), 1.4261
// (d in long double), and phi = pi (x = 9.8696), where sin phi / phi and cos(phi/2) vanish.
struct CoefficientReference {
  LD x;
  LD f[8];
};
// clang-format off
const CoefficientReference kCoefficients[] = {
    {0x1p-56L,
     {9.999999999999999976870e-1L, 4.999999999999999994218e-1L, 1.666666666666666665510e-1L,
      8.333333333333333335261e-2L, -8.333333333333333325623e-2L, -1.666666666666666665565e-2L,
      9.999999999999999982653e-1L, 4.999999999999999997109e-1L}},
    {0x1p-20L,
     {9.999998410542881780807e-1L, 4.999999602635714129266e-1L, 1.666666587193808770699e-1L,
      8.333333465788102508456e-2L, -8.333332803514282197342e-2L, -1.666666590978230360441e-2L,
      9.999998807907128176945e-1L, 4.999999801317853117174e-1L}},
    {0x1p-7L,
     {9.986984251983684679098e-1L, 4.996745639258917220105e-1L, 1.666015746088361075462e-1L,
      8.334418604653040777926e-2L, -8.328993963711694222299e-2L, -1.666046727892488041437e-2L,
      9.990235964353717333376e-1L, 4.998372554771661485872e-1L}},
    {0.25L,
     {9.588510772084060005466e-1L, 4.896697524385091355349e-1L, 1.645956911663759978137e-1L,
      8.368263535405989495948e-2L, -8.195371067444908209269e-2L, -1.646928424247543162486e-2L,
      9.689124217106447841446e-1L, 4.948079185090458591937e-1L}},
    {1L,
     {8.414709848078965066525e-1L, 4.596976941318602825991e-1L, 1.585290151921034933475e-1L,
      8.475613914377404036599e-2L, -7.792440345582405854562e-2L, -1.588935144445019744343e-2L,
      8.775825618903727161163e-1L, 4.794255386042030002733e-1L}},
    {1.375L,
     {7.860824743671734916078e-1L, 4.452707017925618702273e-1L, 1.555763822784192788307e-1L,
      8.530780268552189157387e-2L, -7.597013034032745370673e-2L, -1.560614184923343001068e-2L,
      8.329924324491872082320e-1L, 4.718425064534573437816e-1L}},
    {1.4375L,
     {7.770589566716823924254e-1L, 4.429016672426049086488e-1L, 1.550894214457861617910e-1L,
      8.540074289827002164890e-2L, -7.564826282680168686760e-2L, -1.555937189200248815594e-2L,
      8.256297152291562972974e-1L, 4.705856283624718328553e-1L}},
    {2.5L,
     {6.324217062813903618892e-1L, 4.041369275620836526780e-1L, 1.470313174874438552443e-1L,
      8.702602353295838147426e-2L, -7.034085953711077738669e-2L, -1.478280996009916522199e-2L,
      7.034407157304696662454e-1L, 4.495202595890888501557e-1L}},
    {2.5625L,
     {6.244142418749221393352e-1L, 4.019435081491305984724e-1L, 1.465700519512498968448e-1L,
      8.712437749652214553496e-2L, -7.003815587252255906721e-2L, -1.473820398229037739005e-2L,
      6.964265073817383214288e-1L, 4.482987330726747651001e-1L}},
    {2.625L,
     {6.164607814024936913233e-1L, 3.997595320240227796126e-1L, 1.461101785133357366387e-1L,
      8.722304665731675661945e-2L, -6.973648862687690205788e-2L, -1.469371562513692582993e-2L,
      6.894313702019005907126e-1L, 4.470791496055384037152e-1L}},
    {3.75L,
     {4.822511477604852951105e-1L, 3.620263327040590101560e-1L, 1.380663605972039213039e-1L,
      8.905485441406462125848e-2L, -6.448040470603539338705e-2L, -1.391273309001406766816e-2L,
      5.667456450471316642895e-1L, 4.254564212137707354431e-1L}},
    {3.9921875L,
     {4.554994782769339802403e-1L, 3.542842623515922905008e-1L, 1.363915201184979462412e-1L,
      8.946357350715272501670e-2L, -6.339107229463811525920e-2L, -1.374942885420625865461e-2L,
      5.411241984947876329662e-1L, 4.208825622139697833390e-1L}},
    {4.0078125L,
     {4.537987055676134258529e-1L, 3.537892922051585011836e-1L, 1.362841436400496715221e-1L,
      8.949012406664709007541e-2L, -6.332129530578178907177e-2L, -1.373895079048496240347e-2L,
      5.394807004583264953014e-1L, 4.205884521745446717131e-1L}},
    {6.25L,
     {2.393888576415825976207e-1L, 2.881829784875093943734e-1L, 1.216977827773467843807e-1L,
      9.354531654909428645284e-2L, -5.391633589334979058016e-2L, -1.230565917512495340299e-2L,
      3.153223623952686654475e-1L, 3.795938477422344857394e-1L}},
    {9L,
     {4.704000268662240736691e-2L, 2.211102774000494952524e-1L, 1.058844441459308436259e-1L,
      9.929197039400236964628e-2L, -4.390895023483073145976e-2L, -1.072700611530478173614e-2L,
      7.073720166770291008819e-2L, 3.324983288680181436472e-1L}},
    {9.75L,
     {6.11449171381359340611e-3L, 2.051095099198807609868e-1L, 1.019369752088396314455e-1L,
      1.010353403055707700512e-1L, -4.144661826932799267359e-2L, -1.032835032888596239485e-2L,
      9.546682176614564001881e-3L, 3.202417133353186088237e-1L}},
    {9.875L,
     {-2.732321758992758756608e-4L, 2.025316082417024000567e-1L, 1.012934918659138507216e-1L,
      1.013341308413745708266e-1L, -4.104672897815737478371e-2L, -1.026317644111788882107e-2L,
      -4.293094389827923639975e-4L, 3.18222884344999927644e-1L}},
    {12.1875L,
     {-9.807835092941459943725e-2L, 1.591429925399700297684e-1L, 9.009873648651606969742e-2L,
      1.073350042774203971325e-1L, -3.416322756999833099275e-2L, -9.12026395237564548298e-3L,
      -1.738458777468066140587e-1L, 2.820842006741692984395e-1L}},
    {12.3125L,
     {-1.023448920535760215127e-1L, 1.570185980637932382182e-1L, 8.953054960841226570662e-2L,
      1.07687353568619590962e-1L, -3.381783457308933993495e-2L, -9.061770620218766205213e-3L,
      -1.826314750249060361002e-1L, 2.801951088650489257664e-1L}},
    {20L,
     {-2.171843183512395044731e-1L, 6.189741959902955471393e-2L, 6.085921591756197522366e-2L,
      1.377194557374749519307e-1L, -1.704895787746493069505e-2L, -6.034011407682818547852e-3L,
      -6.172728764571665940589e-1L, 1.759224539378494951904e-1L}},
    {35L,
     {-6.066776227437533895289e-2L, 1.903710691646093644043e-3L, 3.030479320783929539865e-2L,
      4.838308973597045184835e-1L, -1.842148104504786464028e-3L, -2.543161969482051215769e-3L,
      -9.832014355645507097488e-1L, 3.085215301762661136989e-2L}},
};
// clang-format on

}  // namespace

TEMPLATE_TEST_CASE("Rotation vector against 50-digit references (Taylor branches and closed forms)",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  const Vector3<S> vd(S(0.5), S(0.25), S(-0.125));
  const Vector3<S> w(S(-0.25), S(0.5), S(0.375));
  // A few roundings each; measured at most 5.8 eps (long double G vdot at phi = 6.1).
  const LD tol = 16 * eps<S>();
  for (const auto& ref : kReferences) {
    const Vector3<S> v = (Vector3ld(0.25L, -0.375L, 0.75L) * ref.t).template cast<S>();
    INFO("phi = " << static_cast<double>(0.875L * ref.t));
    Matrix3ld r;
    r << ref.r[0], ref.r[1], ref.r[2], ref.r[3], ref.r[4], ref.r[5], ref.r[6], ref.r[7], ref.r[8];
    const Vector3ld omega(ref.r[9], ref.r[10], ref.r[11]);
    const Vector3ld gdot(ref.r[12], ref.r[13], ref.r[14]);
    const Vector3ld vdot(ref.r[15], ref.r[16], ref.r[17]);
    const Eigen::Matrix<LD, 4, 1> q(ref.r[18], ref.r[19], ref.r[20], ref.r[21]);
    const auto rel = [](const auto& a, const auto& b) {
      return (a.template cast<LD>() - b).norm() / b.norm();
    };
    CHECK(rel(P::rotation(v), r) < tol);
    CHECK(rel(Vector3<S>(P::G(v) * vd), omega) < tol);
    CHECK(rel(P::Gdot_thetadot(v, vd), gdot) < tol);
    CHECK(rel(P::thetadot(v, w), vdot) < tol);
    const Eigen::Quaternion<S> qv = P::to_quaternion(v);
    CHECK(rel(Eigen::Matrix<S, 4, 1>(qv.w(), qv.x(), qv.y(), qv.z()), q) < tol);
  }
}

TEMPLATE_TEST_CASE("Rotation vector coefficient functions against 150-digit references",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  // Series below the thresholds, closed forms above: all near eps. Measured at most 9.9 eps (a
  // in float at x = 35, phi = 5.9, from rounding phi = sqrt(x) near 2 pi); the series up to the
  // cap x = 12.25 at most 4.3 eps (c2 in long double at x = 12.19).
  // sin phi / phi and cos(phi/2) vanish at phi = pi: there both forms give them to an absolute
  // eps only (1 - x b is a difference of numbers near 1; sin and cos of sqrt(x) inherit the
  // rounding of phi), which is what R's and the quaternion's entries need. They are measured
  // against max(|f|, 1): relative where |f| >= 1 (at the identity), absolute near pi.
  const LD tol = 16 * eps<S>();
  for (const auto& ref : kCoefficients) {
    INFO("x = " << static_cast<double>(ref.x));
    tumble::detail::rotation_vector::PhiFunctions<S> f(static_cast<S>(ref.x));
    const S got[8] = {f.sinc(), f.a(), f.b(), f.d(), f.c1(), f.c2(), f.half_cos(), f.half_sinc()};
    for (int i = 0; i < 8; ++i) {
      INFO("function " << i);
      const bool zero_at_pi = i == 0 || i == 6;
      const LD scale = zero_at_pi ? std::max(std::abs(ref.f[i]), 1.0L) : std::abs(ref.f[i]);
      CHECK(std::abs(static_cast<LD>(got[i]) - ref.f[i]) / scale < tol);
    }
  }
}

TEMPLATE_TEST_CASE("Rotation vector series and closed forms agree across the thresholds",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  using V = S;
  const auto& lim = tumble::detail::rotation_vector::limits<V>();
  const Vector3<S> n = Vector3<S>(S(2), S(-3), S(6)) / S(7);
  const Vector3<S> vd(S(0.5), S(0.25), S(-0.125));
  const Vector3<S> w(S(-0.25), S(0.5), S(0.375));
  for (const V x : {lim.series, lim.half_cos, lim.half_sinc}) {
    // phi just below (series) and just above (closed form) the threshold: every output changes
    // by O(eps) between the two, not by a jump.
    const S phi = std::sqrt(x);
    const Vector3<S> lo = (phi * (S(1) - S(4) * std::numeric_limits<S>::epsilon())) * n;
    const Vector3<S> hi = (phi * (S(1) + S(4) * std::numeric_limits<S>::epsilon())) * n;
    const LD tol = 32 * eps<S>();
    CHECK(rel_err(P::rotation(lo), P::rotation(hi)) < tol);
    CHECK(rel_err(Vector3<S>(P::G(lo) * vd), Vector3<S>(P::G(hi) * vd)) < tol);
    CHECK(rel_err(P::Gdot_thetadot(lo, vd), P::Gdot_thetadot(hi, vd)) < tol);
    CHECK(rel_err(P::thetadot(lo, w), P::thetadot(hi, w)) < tol);
    CHECK(rel_err(P::to_quaternion(lo).coeffs(), P::to_quaternion(hi).coeffs()) < tol);
  }
  // The thresholds follow from epsilon up to the caps: phi = 3.5 for the coefficient functions
  // (every canonical vector, phi <= pi, from the series), phi = 2 for cos(phi/2).
  CHECK(static_cast<double>(lim.series) == 12.25);
  CHECK(static_cast<double>(lim.half_cos) == 4.0);
}

TEMPLATE_TEST_CASE("Rotation vector R matches Eigen::AngleAxis and is a rotation",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  // phi up to 3 pi: R is periodic in phi.
  for (const auto& s : samples<S>(3 * kPi, 40)) {
    const Matrix3<S> r = P::rotation(s.coords);
    CHECK(rel_err(r, s.reference_rotation()) < 16 * eps<S>());
    const Matrix3ld rl = r.template cast<LD>();
    CHECK((rl.transpose() * rl - Matrix3ld::Identity()).norm() < 16 * eps<S>());
    CHECK(std::abs(rl.determinant() - 1) < 16 * eps<S>());
  }
}

TEMPLATE_TEST_CASE("Rotation vector G, Gdot vdot and the inverse map against finite differences",
                   "[orientation][rotation_vector]", float, double) {
  using S = TestType;
  tumble::test::Random rnd(8);
  for (const auto& s : samples<S>(1.5L * kPi, 30)) {
    const Vector3<S> vd = rnd.vector().cast<S>();
    const Vector3ld vl = s.coords.template cast<LD>(), vdl = vd.template cast<LD>();
    const LD kappa = condition(s.phi);
    const LD tol = 64 * kappa * eps<S>() + kFivePointTol;

    // S(G vdot) = R^T Rdot, Rdot by finite differences of R (Eq. 1.5).
    const Matrix3ld rdot = five_point_derivative(
        [&](LD t) { return Matrix3ld(P::rotation(Vector3ld(vl + t * vdl))); });
    const Matrix3ld wx = P::rotation(vl).transpose() * rdot;
    const Vector3ld omega_fd(wx(2, 1), wx(0, 2), wx(1, 0));
    const Vector3<S> omega = P::G(s.coords) * vd;
    CHECK(rel_err(omega, omega_fd) < tol);
    CHECK((wx + wx.transpose()).norm() < kFivePointTol);  // R^T Rdot is skew

    // Gdot vdot by finite differences of G (Eq. 1.10).
    const Vector3ld gdot_fd =
        five_point_derivative([&](LD t) { return Vector3ld(P::G(Vector3ld(vl + t * vdl)) * vdl); });
    CHECK(rel_err(P::Gdot_thetadot(s.coords, vd), gdot_fd) < tol);

    // The inverse map, both ways, and the accelerations: G vddot + Gdot vdot = alpha.
    const Vector3<S> w = rnd.vector().cast<S>();
    const Vector3<S> alpha = rnd.vector().cast<S>();
    CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) < 16 * kappa * eps<S>());
    CHECK(rel_err(P::thetadot(s.coords, omega), vd) < 16 * kappa * eps<S>());
    const Vector3<S> vdd = P::thetaddot(s.coords, vd, alpha);
    CHECK(rel_err(Vector3<S>(P::G(s.coords) * vdd + P::Gdot_thetadot(s.coords, vd)), alpha) <
          64 * kappa * eps<S>());
  }
}

TEST_CASE("Rotation vector AD derivatives, also at v = 0", "[orientation][rotation_vector]") {
  tumble::test::Random rnd(13);
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-8, 0, 0),
                                      Eigen::Vector3d(0, -6e-9, 8e-9)};
  for (const auto& s : samples<double>(1.8L * kPi, 20)) {
    points.push_back(s.coords);
  }
  for (const auto& v : points) {
    INFO("v = " << v.transpose());
    const Eigen::Vector3d vd = rnd.vector();
    const Vector3<AD> va = along(v, vd);
    // d/dt R(v + t vdot) = R S(G vdot)  (S(omega) = R^T Rdot, Eq. 1.5).
    const Matrix3<AD> ra = P::rotation(va);
    Eigen::Matrix3d rdot;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        rdot(i, j) = ad_derivative(ra(i, j));
      }
    }
    const double kappa = static_cast<double>(condition(static_cast<LD>(v.norm())));
    const Eigen::Vector3d omega = P::G(v) * vd;
    CHECK(rel_err(rdot, Eigen::Matrix3d(P::rotation(v) * tumble::skew(omega))) <
          64 * eps<double>());
    // d/dt (G(v + t vdot) vdot) = Gdot vdot.
    const Vector3<AD> wa = P::G(va) * vd.cast<AD>();
    CHECK(rel_err(P::Gdot_thetadot(v, vd), ad_derivatives(wa)) < 64 * kappa * eps<double>());
    // d/dt q(v + t vdot) = 1/2 q (0, omega) (the quaternion kinematics, Hamilton product).
    const Eigen::Quaternion<AD> qa = P::to_quaternion(va);
    const Eigen::Quaterniond q = P::to_quaternion(v);
    const Eigen::Quaterniond qw(0, omega(0), omega(1), omega(2));
    const Eigen::Vector4d qdot = 0.5 * (q * qw).coeffs();
    const Eigen::Vector4d qdot_ad(ad_derivative(qa.x()), ad_derivative(qa.y()),
                                  ad_derivative(qa.z()), ad_derivative(qa.w()));
    CHECK(rel_err(qdot_ad, qdot) < 64 * eps<double>());
    // d/dt G^-1(v + t vdot) w, by the identity G G^-1 = I: G d(G^-1 w) = -Gdot (G^-1 w) with
    // Gdot = dG/dt along vdot (from AD of G).
    const Eigen::Vector3d w = rnd.vector();
    const Vector3<AD> tda = P::thetadot(va, Vector3<AD>(w.cast<AD>()));
    const Eigen::Vector3d td = P::thetadot(v, w);
    const Vector3<AD> gtd = P::G(va) * td.cast<AD>();
    CHECK(rel_err(Eigen::Vector3d(P::G(v) * ad_derivatives(tda)),
                  Eigen::Vector3d(-ad_derivatives(gtd))) < 64 * kappa * kappa * eps<double>());
  }

  // At v = 0 exactly the derivatives are the known first-order terms, and finite.
  const Eigen::Vector3d vd(0.3, -0.4, 1.2);
  const Vector3<AD> za = along<3>(Eigen::Vector3d::Zero(), vd);
  const Matrix3<AD> r0 = P::rotation(za);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      CHECK(ad_derivative(r0(i, j)) == Approx(tumble::skew(vd)(i, j)).margin(1e-15));
    }
  }
  const Eigen::Quaternion<AD> q0 = P::to_quaternion(za);
  CHECK(ad_derivative(q0.w()) == 0.0);
  CHECK(Eigen::Vector3d(ad_derivative(q0.x()), ad_derivative(q0.y()), ad_derivative(q0.z())) ==
        0.5 * vd);
  // from_quaternion along (1, t e): v = 2 t e + O(t^3).
  const Eigen::Quaternion<AD> qa(
      AD(1.0, Eigen::VectorXd::Zero(1)), AD(0.0, Eigen::VectorXd::Constant(1, vd(0))),
      AD(0.0, Eigen::VectorXd::Constant(1, vd(1))), AD(0.0, Eigen::VectorXd::Constant(1, vd(2))));
  const Vector3<AD> vfromq = P::from_quaternion(qa);
  CHECK(ad_derivatives(vfromq) == 2 * vd);
  const AD dist = P::singularity_distance(za);
  CHECK(dist.value() == Approx(2 * std::acos(-1.0)));
  CHECK(std::isfinite(ad_derivative(dist)));
}

TEMPLATE_TEST_CASE("Rotation vector round trips through R and the quaternion",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  for (const auto& s : samples<S>(1.9L * kPi, 40)) {
    if (std::abs(s.phi - kPi) < 0.1L) {
      continue;  // the axis sign is ill-conditioned at pi; tested below
    }
    // Back from R or q comes the vector with phi <= pi: canonical(v).
    const Vector3<S> c = P::canonical(s.coords);
    // Absolute error ~eps in q is a relative error ~eps / sin(phi/2) in the axis and phi.
    const LD tol = 32 * eps<S>() * condition(s.phi);
    CHECK(rel_err(P::from_rotation(P::rotation(s.coords)), c) < tol);
    const Eigen::Quaternion<S> q = P::to_quaternion(s.coords);
    CHECK(rel_err(P::from_quaternion(q), c) < tol);
    // Against Eigen: q = (cos(phi/2), n sin(phi/2)) (e0 < 0 beyond phi = pi, as in Eigen).
    const Eigen::Quaternion<LD> qe(Eigen::AngleAxis<LD>(s.phi, s.n));
    CHECK(rel_err(q.coeffs(), qe.coeffs()) < 8 * eps<S>());
    // v from q does not depend on the sign or the norm of q.
    const Eigen::Quaternion<S> q2(S(-3) * q.w(), S(-3) * q.x(), S(-3) * q.y(), S(-3) * q.z());
    CHECK(rel_err(P::from_quaternion(q2), c) < tol);
  }
  // A rotation by pi: e0 = 0, phi = pi.
  const Vector3<S> half =
      P::from_quaternion(Eigen::Quaternion<S>(S(0), S(0), S(3) / S(5), S(-4) / S(5)));
  CHECK(rel_err(half, Vector3ld(0, 3 * kPi / 5, -4 * kPi / 5)) < 4 * eps<S>());
  CHECK_THROWS_AS(P::from_quaternion(Eigen::Quaternion<S>(S(0), S(0), S(0), S(0))),
                  std::domain_error);
}

TEMPLATE_TEST_CASE("Rotation vector at and near zero", "[orientation][rotation_vector]", float,
                   double, long double) {
  using S = TestType;
  const Vector3<S> zero = Vector3<S>::Zero();
  const Vector3<S> w(S(0.25), S(-1), S(2));
  CHECK(P::rotation(zero) == Matrix3<S>::Identity());
  CHECK(P::G(zero) == Matrix3<S>::Identity());
  CHECK(P::Gdot_thetadot(zero, w) == zero);
  CHECK(P::thetadot(zero, w) == w);
  CHECK(P::to_quaternion(zero).coeffs() == Eigen::Quaternion<S>::Identity().coeffs());
  CHECK(P::from_quaternion(Eigen::Quaternion<S>::Identity()) == zero);
  CHECK(P::canonical(zero) == zero);
  CHECK(static_cast<double>(P::singularity_distance(zero)) ==
        Approx(2 * std::acos(-1.0)).epsilon(4 * static_cast<double>(eps<S>())));

  // |v| = 1e-8: every output agrees with Eigen and with the first-order terms to rounding.
  for (const auto& s :
       {Sample<S>(1e-8L, Vector3ld(1, 2, -2)), Sample<S>(1e-8L, Vector3ld(0, 0, 1))}) {
    CHECK(rel_err(P::rotation(s.coords), s.reference_rotation()) < 4 * eps<S>());
    // G = I - S(v)/2 + S(v)^2/6 + O(phi^4) (the S^2 term, ~2e-17, matters in long double).
    const Matrix3<S> sk = tumble::skew(s.coords);
    CHECK(rel_err(P::G(s.coords), Matrix3<S>(Matrix3<S>::Identity() - S(0.5) * sk +
                                             (sk * sk) / S(6))) < 4 * eps<S>());
    const Eigen::Quaternion<LD> qe(Eigen::AngleAxis<LD>(s.phi, s.n));
    CHECK(rel_err(P::to_quaternion(s.coords).coeffs(), qe.coeffs()) < 4 * eps<S>());
    const Vector3<S> back = P::from_quaternion(P::to_quaternion(s.coords));
    CHECK((back - s.coords).template cast<LD>().norm() < 4 * eps<S>() * s.phi);
    CHECK(std::abs(static_cast<LD>(P::singularity_distance(s.coords)) - (2 * kPi - s.phi)) <
          8 * eps<S>());
  }
}

TEMPLATE_TEST_CASE("Rotation vector canonical() maps phi > pi to |v| <= pi",
                   "[orientation][rotation_vector]", float, double, long double) {
  using S = TestType;
  const Vector3ld n = Vector3ld(2, -3, 6) / 7;
  // phi <= pi is kept, including phi = pi itself.
  for (const LD phi : {0.5L, 2.0L, 3.0L}) {
    const Sample<S> s(phi, n);
    CHECK(P::canonical(s.coords) == s.coords);
  }
  const Vector3<S> at_pi(S(0), S(0), static_cast<S>(kPi));
  CHECK(P::canonical(at_pi) == at_pi);
  // phi > pi: (phi - 2 pi k) n with k = round(phi / (2 pi)), the same attitude.
  for (const LD phi : {3.3L, 5.0L, 2 * kPi - 1e-3L, 7.0L, 3 * kPi + 0.1L, 12.0L}) {
    const Sample<S> s(phi, n);
    const Vector3<S> c = P::canonical(s.coords);
    const LD k = std::round(s.phi / (2 * kPi));
    const Vector3ld expected = (s.phi - 2 * kPi * k) * s.n;
    INFO("phi = " << static_cast<double>(phi));
    CHECK((c.template cast<LD>() - expected).norm() < 16 * eps<S>() * s.phi);
    CHECK(static_cast<LD>(c.norm()) <= kPi + 16 * eps<S>());
    CHECK(rel_err(P::rotation(c), s.reference_rotation()) < 16 * eps<S>() * s.phi);
    CHECK(static_cast<LD>(P::singularity_distance(c)) >= kPi - 16 * eps<S>());
  }
}

TEMPLATE_TEST_CASE("Rotation vector near the 360 degree singularity",
                   "[orientation][rotation_vector]", float, double) {
  using S = TestType;
  // phi = 2 pi - 1e-3: cond(G) = (phi/2) / sin(phi/2) ~ 6.3e3.
  const Sample<S> s(2 * kPi - 1e-3L, Vector3ld(2, -3, 6));
  const LD kappa = condition(s.phi);
  CHECK(rel_err(P::rotation(s.coords), s.reference_rotation()) < 16 * eps<S>());
  CHECK(std::abs(static_cast<LD>(P::singularity_distance(s.coords)) - (2 * kPi - s.phi)) <
        8 * eps<S>() * s.phi);
  const Vector3<S> w(S(0.3), S(-0.1), S(0.2));
  CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) < 16 * kappa * eps<S>());

  // Switching to canonical(v) (norm 1e-3, far from the singularity) keeps omega, with the rate
  // of the new vector G(c)^-1 G(v) vdot = d/dt canonical(v + t vdot) (finite differences).
  tumble::test::Random rnd(3);
  const Vector3<S> vd = rnd.vector().template cast<S>();
  const Vector3<S> c = P::canonical(s.coords);
  const Vector3<S> cd = P::thetadot(c, Vector3<S>(P::G(s.coords) * vd));
  const Vector3ld vl = s.coords.template cast<LD>(), vdl = vd.template cast<LD>();
  const Vector3ld cd_fd = five_point_derivative(
      [&](LD t) { return Vector3ld(P::canonical(Vector3ld(vl + t * vdl))); }, 1e-6L);
  CHECK(rel_err(cd, cd_fd) < 64 * kappa * eps<S>() + 1e-9L);
}

TEST_CASE("Rotation vector distance to the singularity", "[orientation][rotation_vector]") {
  // |phi - 2 pi k| for the nearest k >= 1.
  const double two_pi = 2 * std::acos(-1.0);
  const Eigen::Vector3d n(0.6, 0, -0.8);
  for (const double phi : {0.0, 1.0, two_pi / 2, 5.0, two_pi - 0.01, two_pi + 0.5, 9.0, 12.0}) {
    const double k = std::max(1.0, std::round(phi / two_pi));
    CHECK(P::singularity_distance(Eigen::Vector3d(phi * n)) ==
          Approx(std::abs(phi - k * two_pi)).epsilon(1e-14).margin(1e-14));
  }
}

TEST_CASE("Rotation vector AD with constant and variable arguments mixed",
          "[orientation][rotation_vector]") {
  // Eigen's AutoDiffScalar gives constants empty derivative vectors; every function must accept
  // any mix of constant and variable arguments (9 derivatives: theta, thetadot, omega).
  const auto make = [](const Eigen::Vector3d& x, bool variable, int first) {
    Vector3<AD> r;
    for (int i = 0; i < 3; ++i) {
      r(i) = variable ? AD(x(i), 9, first + i) : AD(x(i));
    }
    return r;
  };
  for (const double scale : {0.0, 1e-8, 1.0, 20.0}) {
    for (int mask = 0; mask < 8; ++mask) {
      INFO("scale = " << scale << ", mask = " << mask);
      const Eigen::Vector3d th_d = scale * Eigen::Vector3d(0.3, 0.1, -0.1);
      const Vector3<AD> th = make(th_d, (mask & 1) != 0, 0);
      const Vector3<AD> thd = make(Eigen::Vector3d(0.1, 0.4, 0.7), (mask & 2) != 0, 3);
      const Vector3<AD> w = make(Eigen::Vector3d(1, 2, 3), (mask & 4) != 0, 6);
      const Vector3<AD> omega = P::G(th) * thd;
      const Vector3<AD> values[] = {omega,
                                    P::Gdot_thetadot(th, thd),
                                    P::thetadot(th, w),
                                    P::thetaddot(th, thd, w),
                                    P::from_rotation(P::rotation(th)),
                                    P::from_quaternion(P::to_quaternion(th)),
                                    P::canonical(th)};
      const Eigen::Vector3d omega_d = P::G(th_d) * Eigen::Vector3d(0.1, 0.4, 0.7);
      CHECK(rel_err(Eigen::Vector3d(omega(0).value(), omega(1).value(), omega(2).value()),
                    omega_d) < 4 * eps<double>());
      for (const auto& v : values) {
        for (int i = 0; i < 3; ++i) {
          CHECK(std::isfinite(v(i).value()));
          CHECK(tumble::detail::all_finite(v(i).derivatives()));
        }
      }
      CHECK(std::isfinite(P::singularity_distance(th).value()));
    }
  }
}

TEST_CASE("Rotation vector AD derivative of the distance to the singularity",
          "[orientation][rotation_vector]") {
  // d/dt of the distance along thetadot, against central differences in long double.
  tumble::test::Random rnd(77);
  for (const double phi : {0.5, 1.5, 2.5, 3.5, 5.0, 6.0, 7.0, 9.0}) {
    const Eigen::Vector3d n = rnd.vector().normalized();
    const Eigen::Vector3d th = (phi)*n;
    const Eigen::Vector3d thd = rnd.vector();
    const AD dist = P::singularity_distance(along(th, thd));
    const Vector3ld thl = th.cast<LD>(), thdl = thd.cast<LD>();
    const LD fd = five_point_derivative(
        [&](LD t) {
          return Eigen::Matrix<LD, 1, 1>(P::singularity_distance(Vector3ld(thl + t * thdl)));
        },
        1e-4L * std::min(1.0L, thl.norm() / thdl.norm()))(0);  // |.| varies on the scale |theta|
    INFO("phi = " << phi);
    CHECK(std::abs(ad_derivative(dist) - fd) <
          64 * eps<double>() * std::max(1.0L, std::abs(fd)) + kFivePointTol);
  }
}
