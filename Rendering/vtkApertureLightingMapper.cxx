// SPDX-License-Identifier: BSD-3-Clause
#include "vtkApertureLightingMapper.h"

#include "vtkApertureExposureDecFS.h"
#include "vtkApertureExposureImplFS.h"
#include "vtkApertureLightingDecFS.h"
#include "vtkApertureLightingDecVS.h"
#include "vtkApertureLightingImplFS.h"
#include "vtkApertureLightingImplVS.h"
#include "vtkApertureLightingModel.h"
#include "vtkApertureToneMapFS.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkDataObject.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkOpenGLHelper.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"

#include "ap_light.h"

#include <algorithm>
#include <vector>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkApertureLightingMapper);

namespace
{
const double kPi = 3.14159265358979323846;
const double kDeg = kPi / 180.0;

// The sun cap's angular radius as drawn, radians: the disc's radius times the user's scale, at
// most 90 degrees (the shader and the CPU reference must use the same).
// (a radius below the model's least, 1e-6 rad, is that: a point sun, as the shader drew it,
// where the CPU reference failed naming no parameter until 2026-12-07)
double DrawnSunRadius(double degrees, double scale)
{
  return std::max(AP_LIGHT_MIN_SUN_RADIUS, std::min(90.0, degrees * scale) * kDeg);
}

void Insert(std::string& source, const char* tag, const char* code)
{
  // Keep the tag (the superclass expands it afterwards) and add our code after it.
  vtkShaderProgram::Substitute(source, tag, std::string(tag) + "\n" + code, false);
}
}

//------------------------------------------------------------------------------
vtkApertureLightingMapper::vtkApertureLightingMapper() = default;

vtkApertureLightingMapper::~vtkApertureLightingMapper()
{
  if (this->SkyTable)
  {
    this->SkyTable->UnRegister(this);
  }
  if (this->SkyTexture)
  {
    this->SkyTexture->Delete();
  }
}

void vtkApertureLightingMapper::SetSkyTable(
  vtkFloatArray* table, int azimuths, int elevations, int radii)
{
  if (table &&
    (azimuths < 4 || azimuths > 256 || elevations < 2 || elevations > 256 || radii < 2 ||
      radii > 256 || table->GetNumberOfComponents() != 3 ||
      table->GetNumberOfTuples() != static_cast<vtkIdType>(azimuths) * elevations * radii))
  {
    vtkErrorMacro(<< "SetSkyTable: expected 3 components and azimuths x elevations x radii "
                     "tuples with sizes within 4..256, 2..256, 2..256; keeping the previous sky");
    return;
  }
  const bool variantChanges = (table != nullptr) != (this->SkyTable != nullptr);
  if (table)
  {
    table->Register(this);
  }
  if (this->SkyTable)
  {
    this->SkyTable->UnRegister(this);
  }
  this->SkyTable = table;
  if (variantChanges)
  {
    this->VariantTime.Modified(); // on or off: compile the other shader variant
  }
  this->SkyTableSize[0] = azimuths;
  this->SkyTableSize[1] = elevations;
  this->SkyTableSize[2] = radii;
  this->SkyTextureTime = 0; // upload at the next draw (a uniform-like change: no Modified)
}

void vtkApertureLightingMapper::RenderPieceFinish(vtkRenderer* ren, vtkActor* act)
{
  if (this->SkyTexture && this->SkyTexture->IsBound())
  {
    this->SkyTexture->Deactivate();
  }
  this->Superclass::RenderPieceFinish(ren, act);
}

void vtkApertureLightingMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->SkyTexture)
  {
    this->SkyTexture->ReleaseGraphicsResources(window);
    this->SkyTextureTime = 0;
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::SetNormalArrayName(const char* name)
{
  this->SetModelArrayName(this->NormalName, name);
}

void vtkApertureLightingMapper::SetBentNormalArrayName(const char* name)
{
  this->SetModelArrayName(this->BentName, name);
}

void vtkApertureLightingMapper::SetApertureRadiusArrayName(const char* name)
{
  this->SetModelArrayName(this->RadiusName, name);
}

void vtkApertureLightingMapper::SetModelArrayName(std::string& field, const char* name)
{
  const std::string value = name ? name : "";
  if (value == field)
  {
    return;
  }
  field = value;
  this->MapArrays(); // (VTK's vertex attributes name the arrays: the next upload reads these)
  this->Modified();
}

// The lighting parameters below are uniforms: no Modified(), so nothing is rebuilt.
void vtkApertureLightingMapper::SetSunDirection(double x, double y, double z)
{
  // (scaled by the largest component first: the squares of 1e300 or 1e-320 overflow or vanish)
  const double m = std::max(std::fabs(x), std::max(std::fabs(y), std::fabs(z)));
  // (std::max drops a NaN that is not its first argument: each component checked)
  if (!(m > 0.0) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
  {
    vtkErrorMacro(<< "SetSunDirection: the direction (" << x << ", " << y << ", " << z
                  << ") has no finite, non-zero length; keeping (" << this->SunDirection[0]
                  << ", " << this->SunDirection[1] << ", " << this->SunDirection[2] << ")");
    return;
  }
  x /= m;
  y /= m;
  z /= m;
  const double n = std::sqrt(x * x + y * y + z * z);
  this->SunDirection[0] = x / n;
  this->SunDirection[1] = y / n;
  this->SunDirection[2] = z / n;
}

void vtkApertureLightingMapper::SetSunAngularRadius(double degrees)
{
  if (!(degrees > 0.0 && degrees <= 90.0))
  {
    vtkErrorMacro(<< "SetSunAngularRadius: " << degrees << " is not within (0, 90] degrees");
    return;
  }
  this->SunAngularRadius = degrees;
}

void vtkApertureLightingMapper::SetSunScale(double scale)
{
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    vtkErrorMacro(<< "SetSunScale: " << scale << " is not a positive factor");
    return;
  }
  this->SunScale = scale;
}

void vtkApertureLightingMapper::SetSunIrradiance(double r, double g, double b)
{
  if (!(r >= 0.0 && g >= 0.0 && b >= 0.0) || !std::isfinite(r + g + b))
  {
    vtkErrorMacro(<< "SetSunIrradiance: irradiances must be finite and not negative");
    return;
  }
  this->SunIrradiance[0] = r;
  this->SunIrradiance[1] = g;
  this->SunIrradiance[2] = b;
}

void vtkApertureLightingMapper::SetSkyRadiance(double r, double g, double b)
{
  if (!(r >= 0.0 && g >= 0.0 && b >= 0.0) || !std::isfinite(r + g + b))
  {
    vtkErrorMacro(<< "SetSkyRadiance: radiances must be finite and not negative");
    return;
  }
  this->SkyRadiance[0] = r;
  this->SkyRadiance[1] = g;
  this->SkyRadiance[2] = b;
}

// The modes and the shading frequency select compiled shader variants: a change rebuilds the
// shaders at the next draw (VariantTime), but not the geometry.
void vtkApertureLightingMapper::SetIntersectionMode(int mode)
{
  mode = mode == SMOOTHSTEP ? SMOOTHSTEP : EXACT;
  if (mode != this->IntersectionMode)
  {
    this->IntersectionMode = mode;
    this->VariantTime.Modified();
  }
}

void vtkApertureLightingMapper::SetLambertMode(int mode)
{
  mode = mode == EXACT_CAP ? EXACT_CAP : CENTROID;
  if (mode != this->LambertMode)
  {
    this->LambertMode = mode;
    this->VariantTime.Modified();
  }
}

void vtkApertureLightingMapper::SetShadingFrequency(int frequency)
{
  frequency = frequency == PER_VERTEX ? PER_VERTEX : PER_FRAGMENT;
  if (frequency != this->ShadingFrequency)
  {
    this->ShadingFrequency = frequency;
    this->VariantTime.Modified();
  }
}

bool vtkApertureLightingMapper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  return cellBO.ShaderSourceTime < this->VariantTime ||
    this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act);
}

void vtkApertureLightingMapper::SetExposure(double ev)
{
  if (std::isnan(ev))
  {
    vtkErrorMacro(<< "SetExposure: NaN");
    return;
  }
  this->Exposure = std::max(-30.0, std::min(30.0, ev));
}

void vtkApertureLightingMapper::SetToneMapping(bool on)
{
  this->ToneMapping = on;
}

//------------------------------------------------------------------------------
bool vtkApertureLightingMapper::CheckInput(vtkPolyData* mesh)
{
  vtkPolyData* input = mesh ? mesh : this->GetInput();
  if (!input)
  {
    this->InputProblem = "no input";
    return false;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const std::pair<const std::string*, int> wanted[3] = { { &this->NormalName, 3 },
    { &this->BentName, 3 }, { &this->RadiusName, 1 } };
  for (const auto& w : wanted)
  {
    vtkDataArray* a = input->GetPointData()->GetArray(w.first->c_str());
    if (!a)
    {
      this->InputProblem = "the mesh has no point array '" + *w.first +
        "' (bake it with vtkApertureSkyVisibility and mesh the result, or set the array names)";
      return false;
    }
    if (a->GetNumberOfComponents() != w.second || a->GetNumberOfTuples() != n)
    {
      this->InputProblem = "the point array '" + *w.first + "' has " +
        std::to_string(a->GetNumberOfComponents()) + " component(s) and " +
        std::to_string(a->GetNumberOfTuples()) + " tuples; expected " +
        std::to_string(w.second) + " and " + std::to_string(n) + " (one per point)";
      return false;
    }
  }
  this->InputProblem.clear();
  return true;
}

void vtkApertureLightingMapper::MapArrays()
{
  // (only the model's own: a script's MapDataArrayToVertexAttribute for its own shader
  // replacements stays mapped)
  for (const char* attribute : { "apertureNormalMC", "apertureBentMC", "apertureRadiusMC" })
  {
    this->RemoveVertexAttributeMapping(attribute);
  }
  if (this->UsingAperture)
  {
    const int points = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    this->MapDataArrayToVertexAttribute("apertureNormalMC", this->NormalName.c_str(), points, -1);
    this->MapDataArrayToVertexAttribute("apertureBentMC", this->BentName.c_str(), points, -1);
    this->MapDataArrayToVertexAttribute("apertureRadiusMC", this->RadiusName.c_str(), points, -1);
  }
}

void vtkApertureLightingMapper::DropResizedSkyTable(const char* where)
{
  vtkFloatArray* t = this->SkyTable;
  const vtkIdType tuples = static_cast<vtkIdType>(this->SkyTableSize[0]) *
    this->SkyTableSize[1] * this->SkyTableSize[2];
  if (!t || (t->GetNumberOfComponents() == 3 && t->GetNumberOfTuples() == tuples))
  {
    return;
  }
  // (a segfault until 2026-12-06: the upload and the lookups read the sizes given)
  vtkErrorMacro(<< where << "the sky table now has " << t->GetNumberOfTuples()
                << " tuples of " << t->GetNumberOfComponents() << " components, not the "
                << this->SkyTableSize[0] << " x " << this->SkyTableSize[1] << " x "
                << this->SkyTableSize[2] << " RGB tuples given to SetSkyTable; shading with "
                << "the uniform SkyRadiance instead");
  this->SetSkyTable(nullptr, 0, 0, 0);
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::RenderPiece(vtkRenderer* ren, vtkActor* act)
{
  this->DropResizedSkyTable("");
  bool aperture = false;
  if (this->LightingModel == APERTURE)
  {
    aperture = this->CheckInput();
    if (!aperture)
    {
      vtkErrorMacro(<< "cannot shade with the aperture model: " << this->InputProblem
                    << "; drawing with standard lighting");
    }
  }
  if (aperture != this->UsingAperture)
  {
    // Shaders and vertex attributes change: rebuild both (once, on a model switch).
    this->UsingAperture = aperture;
    this->MapArrays();
    this->Modified();
  }
  this->DrewWithGeometryShader = false;
  this->Superclass::RenderPiece(ren, act);
  if (this->UsingAperture && this->DrewWithGeometryShader)
  {
    this->InputProblem = "VTK draws this actor's edges (EdgeVisibility) or wide lines "
                         "(RenderLinesAsTubes, LineWidth) with a geometry shader, which the "
                         "aperture model does not pass its arrays through";
    vtkErrorMacro(<< "cannot shade with the aperture model: " << this->InputProblem
                  << "; drawing with standard lighting");
  }
}

void vtkApertureLightingMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  ++this->GeometryUploads;
  this->Superclass::BuildBufferObjects(ren, act);
}

// Whether a program has a geometry shader: VTK 9.1 adds one for edges over a surface and for
// lines drawn wide or as tubes, and it passes on only VTK's own varyings, so the aperture
// model's arrived as zero (every point black).
static bool HasGeometryShader(vtkShader* shader)
{
  return shader && !shader->GetSource().empty();
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  if (this->UsingAperture && !HasGeometryShader(shaders[vtkShader::Geometry]))
  {
    // Variants are compiled, not branched on uniforms (llvmpipe runs untaken branches, masked):
    // the sky table, where the model runs (per pixel or per vertex), and the two modes.
    const bool perVertex = this->ShadingFrequency == PER_VERTEX;
    const std::string defines = std::string(this->SkyTable ? "#define AP_SKY_TABLE 1\n" : "") +
      (perVertex ? "#define AP_PER_VERTEX 1\n" : "") +
      (this->IntersectionMode == SMOOTHSTEP ? "#define AP_SMOOTHSTEP 1\n" : "") +
      (this->LambertMode == EXACT_CAP ? "#define AP_EXACT_CAP 1\n" : "");
    const std::string decVS = defines + vtkApertureLightingDecVS +
      (perVertex ? std::string(vtkApertureLightingModel) : std::string());
    const std::string decFS = defines + vtkApertureLightingDecFS +
      (perVertex ? std::string() : std::string(vtkApertureLightingModel));
    Insert(vs, "//VTK::Normal::Dec", decVS.c_str());
    Insert(vs, "//VTK::Normal::Impl", vtkApertureLightingImplVS);
    Insert(fs, "//VTK::Light::Dec", decFS.c_str());
    Insert(fs, "//VTK::Light::Impl", vtkApertureLightingImplFS);
    Insert(fs, "//VTK::TCoord::Impl", vtkApertureToneMapFS);
  }
  else
  {
    Insert(fs, "//VTK::Light::Dec", vtkApertureExposureDecFS);
    Insert(fs, "//VTK::Light::Impl", vtkApertureExposureImplFS);
  }
  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Fragment]->SetSource(fs);
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  vtkShaderProgram* program = cellBO.Program;
  const bool standIn = this->LightingModel == APERTURE &&
    (!this->UsingAperture || (program && HasGeometryShader(program->GetGeometryShader())));
  this->DrewWithGeometryShader |= this->UsingAperture && standIn;
  // VTK's lighting standing in for the aperture model is drawn as VTK draws it, without the
  // Exposure: the model's, near -7 EV for sunlight in W/m^2, left it black.
  const float exposure = standIn ? 1.0f : static_cast<float>(std::exp2(this->Exposure));
  if (program && program->IsUniformUsed("apertureExposureScale"))
  {
    program->SetUniformf("apertureExposureScale", exposure);
  }
  if (program && this->UsingAperture && program->IsUniformUsed("apertureSunDirection"))
  {
    float dir[3], sky[3];
    for (int c = 0; c < 3; ++c)
    {
      dir[c] = static_cast<float>(this->SunDirection[c]);
      sky[c] = static_cast<float>(this->SkyRadiance[c]);
    }
    const double rl = DrawnSunRadius(this->SunAngularRadius, this->SunScale);
    program->SetUniform3f("apertureSunDirection", dir);
    program->SetUniformf("apertureSunRadius", static_cast<float>(rl));
    // per-draw constants of the shader, computed once here rather than per fragment
    const double sinRl = std::sin(rl), halfSin = std::sin(0.5 * rl);
    float radiance[3];
    for (int c = 0; c < 3; ++c)
    {
      radiance[c] = static_cast<float>(this->SunIrradiance[c] / (kPi * sinRl * sinRl));
    }
    program->SetUniformf("apertureSunSin", static_cast<float>(sinRl));
    program->SetUniformf("apertureSunCos", static_cast<float>(std::cos(rl)));
    const float half[2] = { static_cast<float>(halfSin), static_cast<float>(std::cos(0.5 * rl)) };
    program->SetUniform2f("apertureSunHalf", half);
    program->SetUniformf("apertureSunArea", static_cast<float>(4.0 * kPi * halfSin * halfSin));
    program->SetUniform3f("apertureSunRadiance", radiance);
    program->SetUniform3f("apertureSkyRadiance", sky);
    program->SetUniformi("apertureToneMap", this->ToneMapping ? 1 : 0);
    if (this->SkyTable)
    {
      auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
      if (!this->SkyTexture)
      {
        this->SkyTexture = vtkTextureObject::New();
      }
      if (window && (this->SkyTextureTime < this->SkyTable->GetMTime() ||
                      this->SkyTexture->GetContext() != window))
      {
        this->SkyTexture->SetContext(window);
        this->SkyTexture->SetMinificationFilter(vtkTextureObject::Nearest);
        this->SkyTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
        this->SkyTexture->SetWrapS(vtkTextureObject::ClampToEdge);
        this->SkyTexture->SetWrapT(vtkTextureObject::ClampToEdge);
        this->SkyTexture->Create2DFromRaw(static_cast<unsigned int>(this->SkyTableSize[0]),
          static_cast<unsigned int>(this->SkyTableSize[1] * this->SkyTableSize[2]), 3, VTK_FLOAT,
          this->SkyTable->GetPointer(0));
        this->SkyTextureTime = this->SkyTable->GetMTime();
      }
      if (window)
      {
        this->SkyTexture->Activate();
        program->SetUniformi("apertureSkyTable", this->SkyTexture->GetTextureUnit());
        program->SetUniform1iv("apertureSkyTableSize", 3, this->SkyTableSize);
      }
    }
  }
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
}

//------------------------------------------------------------------------------
bool vtkApertureLightingMapper::ComputeReference(vtkPolyData* mesh, const double albedo[3],
  vtkDoubleArray* radiance, vtkUnsignedCharArray* display)
{
  if (!mesh || !this->CheckInput(mesh))
  {
    if (!mesh)
    {
      this->InputProblem = "no mesh";
    }
    vtkErrorMacro(<< "ComputeReference: " << this->InputProblem);
    return false;
  }
  if (!albedo || !(albedo[0] >= 0.0 && albedo[0] <= 1.0 && albedo[1] >= 0.0 &&
                   albedo[1] <= 1.0 && albedo[2] >= 0.0 && albedo[2] <= 1.0))
  {
    // (the model takes such a point as nodata: every point NaN and black, without a word)
    std::ostringstream msg;
    msg << "the albedo must be RGB within [0, 1]";
    if (albedo)
    {
      msg << ", not (" << albedo[0] << ", " << albedo[1] << ", " << albedo[2] << ")";
    }
    this->InputProblem = msg.str();
    vtkErrorMacro(<< "ComputeReference: " << this->InputProblem);
    return false;
  }
  ap_light_params p;
  ap_light_params_init(&p);
  for (int c = 0; c < 3; ++c)
  {
    p.sun[c] = this->SunDirection[c];
    p.sun_irradiance[c] = this->SunIrradiance[c];
    p.sky_radiance[c] = this->SkyRadiance[c];
  }
  p.sun_radius = DrawnSunRadius(this->SunAngularRadius, this->SunScale);
  p.intersection = this->IntersectionMode == SMOOTHSTEP ? AP_LIGHT_SMOOTHSTEP : AP_LIGHT_EXACT;
  p.lambert = this->LambertMode == EXACT_CAP ? AP_LIGHT_EXACTCAP : AP_LIGHT_CENTROID;
  p.exposure = this->Exposure;
  this->DropResizedSkyTable("ComputeReference: ");
  if (this->SkyTable)
  {
    p.sky_table = this->SkyTable->GetPointer(0);
    for (int k = 0; k < 3; ++k)
    {
      p.sky_table_size[k] = this->SkyTableSize[k];
    }
  }

  // The arrays as contiguous float, as the GPU receives them; vectors normalised as the
  // shader does where its apUsable takes them (no NaN, the largest component in magnitude
  // within [2^-100, 2^62): compared, not computed, so that both sides agree, and far enough
  // above the subnormals a GPU flushes to 0 that those do not matter), scaled by that
  // component first, else NaN, nodata, as it draws them (ap_light takes unit vectors only,
  // within 1e-4: normals 5e-4 long, as half floats round them, were nodata here and lit on
  // the GPU, until 2026-12-07).
  const vtkIdType n = mesh->GetNumberOfPoints();
  auto floats = [n, mesh](const std::string& name, int comps) {
    std::vector<float> v(static_cast<size_t>(n) * comps);
    vtkDataArray* a = mesh->GetPointData()->GetArray(name.c_str());
    for (vtkIdType i = 0; i < n; ++i)
    {
      float* t = v.data() + static_cast<size_t>(i) * comps;
      bool nan = false;
      float largest = 0.0f;
      for (int c = 0; c < comps; ++c)
      {
        t[c] = static_cast<float>(a->GetComponent(i, c));
        nan = nan || std::isnan(t[c]);
        largest = std::max(largest, std::fabs(t[c]));
      }
      if (comps == 3)
      {
        const bool usable =
          !nan && largest >= 7.8886091e-31f && largest < 4.611686e18f;
        float length2 = 0.0f;
        for (int c = 0; c < 3; ++c)
        {
          t[c] = usable ? t[c] / largest : std::numeric_limits<float>::quiet_NaN();
          length2 += t[c] * t[c];
        }
        const float length = std::sqrt(length2);
        for (int c = 0; c < 3; ++c)
        {
          t[c] /= length;
        }
      }
    }
    return v;
  };
  const std::vector<float> normals = floats(this->NormalName, 3);
  const std::vector<float> bent = floats(this->BentName, 3);
  const std::vector<float> rp = floats(this->RadiusName, 1);
  const float a[3] = { static_cast<float>(albedo[0]), static_cast<float>(albedo[1]),
    static_cast<float>(albedo[2]) };
  std::vector<float> lo(radiance ? 3 * static_cast<size_t>(n) : 0);
  std::vector<unsigned char> rgb(display ? 3 * static_cast<size_t>(n) : 0);
  const ap_status st = ap_light_points(&p, static_cast<size_t>(n), normals.data(), bent.data(),
    rp.data(), a, 0, radiance ? lo.data() : nullptr, display ? rgb.data() : nullptr);
  if (st != AP_OK)
  {
    this->InputProblem = std::string("the lighting parameters are out of range: ") +
      ap_status_string(st);
    vtkErrorMacro(<< "ComputeReference: " << this->InputProblem);
    return false;
  }
  if (radiance)
  {
    radiance->SetNumberOfComponents(3);
    radiance->SetNumberOfTuples(n);
    for (size_t k = 0; k < lo.size(); ++k)
    {
      radiance->SetValue(static_cast<vtkIdType>(k), lo[k]);
    }
    radiance->Modified(); // (new values in an array of the same size: consumers must see them)
  }
  if (display)
  {
    display->SetNumberOfComponents(3);
    display->SetNumberOfTuples(n);
    std::copy(rgb.begin(), rgb.end(), display->GetPointer(0));
    display->Modified();
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkApertureLightingMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LightingModel: " << (this->LightingModel == APERTURE ? "APERTURE" : "STANDARD")
     << "\n";
  os << indent << "Arrays: " << this->NormalName << ", " << this->BentName << ", "
     << this->RadiusName << "\n";
  os << indent << "SunDirection: " << this->SunDirection[0] << " " << this->SunDirection[1] << " "
     << this->SunDirection[2] << "\n";
  os << indent << "SunAngularRadius: " << this->SunAngularRadius << " x " << this->SunScale << "\n";
  os << indent << "SunIrradiance: " << this->SunIrradiance[0] << " " << this->SunIrradiance[1]
     << " " << this->SunIrradiance[2] << "\n";
  os << indent << "SkyRadiance: " << this->SkyRadiance[0] << " " << this->SkyRadiance[1] << " "
     << this->SkyRadiance[2] << "\n";
  os << indent << "IntersectionMode: " << (this->IntersectionMode == EXACT ? "EXACT" : "SMOOTHSTEP")
     << "\n";
  os << indent << "LambertMode: " << (this->LambertMode == CENTROID ? "CENTROID" : "EXACT_CAP")
     << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "ToneMapping: " << this->ToneMapping << "\n";
  os << indent << "ShadingFrequency: "
     << (this->ShadingFrequency == PER_VERTEX ? "PER_VERTEX" : "PER_FRAGMENT") << "\n";
  os << indent << "SkyTable: ";
  if (this->SkyTable)
  {
    os << this->SkyTable << " (" << this->SkyTableSize[0] << " x " << this->SkyTableSize[1]
       << " x " << this->SkyTableSize[2] << ")\n";
  }
  else
  {
    os << "(none: the uniform SkyRadiance)\n";
  }
  os << indent << "GeometryUploads: " << this->GeometryUploads << "\n";
  os << indent << "InputProblem: " << (this->InputProblem.empty() ? "(none)" : this->InputProblem)
     << "\n";
}
