// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkApertureLightingMapper
 * @brief   Terrain mapper that shades a mesh with the sun and the sky through each point's
 *          aperture (ambient aperture lighting, Oat & Sander 2007), in one pass on the GPU.
 *
 * Input: a terrain mesh (vtkApertureTerrainMesh) carrying, as point arrays in its own
 * East-North-Up frame, the surface normals ("Normals"), the bent normal ("BentNormal", 3
 * components) and the aperture radius ("ApertureRadius", radians) of
 * vtkApertureSkyVisibility; the names are configurable. Every quantity below is in that frame.
 *
 * The model (exactly that of the CPU reference ap_light.h, which documents every formula):
 * the visible sky of a point is the spherical cap of axis BentNormal and radius
 * ApertureRadius. The sun is a cap of angular radius SunAngularRadius x SunScale around
 * SunDirection; the part of it inside the aperture (IntersectionMode EXACT: the closed form, in
 * its float-safe half-angle form; SMOOTHSTEP: Oat & Sander's approximation) lights the point
 * with a Lambert term (LambertMode CENTROID: the visible area times the cosine of its centroid;
 * EXACT_CAP: the sun cap's exact cosine integral, clipped by the surface's plane, times the
 * visible fraction). The rest of the aperture is filled with SkyRadiance, cosine-weighted. The
 * albedo is the actor's colour, or its scalar colours, times its texture if it has one (and
 * times the property's Diffuse, as VTK's diffuse colour is). The property's other lighting
 * settings (Lighting, Interpolation, Ambient, Specular, PBR) do not apply to this model, and
 * back faces are lit as their front is: there is no light from below the terrain. The
 * outgoing radiance (W/m²/sr for irradiances in W/m²) is multiplied by 2^Exposure and, with
 * ToneMapping on (default), mapped by 1 − exp(−x) and the sRGB transfer function for display.
 *
 * Moving the sun, changing the sky, the exposure or the tone mapping changes uniforms only
 * (SetSkyTable uploads its small texture, not the geometry): these setters do not mark the
 * mapper modified (no ModifiedEvent, GetMTime unchanged: an observer of either sees nothing),
 * so the next Render() uses them and no geometry is uploaded again (GetGeometryUploads()
 * counts uploads, for tests). The modes, the shading frequency and switching the sky table on
 * or off select compiled shader variants: the next Render() compiles (or takes from VTK's
 * shader cache) the variant, again without a geometry upload, and do not mark it modified
 * either. The array-name setters and LightingModel do.
 *
 * LightingModel STANDARD draws with VTK's own lighting (times 2^Exposure) and needs no arrays.
 * With the default APERTURE model, missing or wrongly sized arrays are an error (vtkErrorMacro
 * once per render) and the mesh is drawn with VTK's standard lighting instead, as a plain
 * vtkPolyDataMapper draws it, without the Exposure (documented fallback; never a shader compile
 * failure). So are an actor's edges over its surface (EdgeVisibility) and lines drawn wide or
 * as tubes, for which VTK adds a geometry shader that passes on only its own varyings. NaN
 * arrays, negative radii and vectors whose largest component (in magnitude) is below 2^-100
 * or 2^62 and above (nodata) give black points; normals and bent
 * normals of other lengths are normalised, and radii beyond pi/2 (+inf too) taken as pi/2. A
 * setter given a value outside its documented range (a zero or non-finite sun direction, say)
 * reports an error (vtkErrorMacro) and keeps the previous value, except Exposure, which is
 * clamped to its range (NaN is refused); the mode setters take an unknown value as their
 * default (EXACT, CENTROID, PER_FRAGMENT). Vertex attributes a script maps for its own shader
 * replacements (MapDataArrayToVertexAttribute) are kept.
 *
 * @sa vtkApertureSolarPosition vtkApertureSkyVisibility vtkApertureTerrainMesh
 */
#ifndef vtkApertureLightingMapper_h
#define vtkApertureLightingMapper_h

#include "ApertureRenderingModule.h" // for export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <string> // for std::string

class vtkDoubleArray;
class vtkFloatArray;
class vtkTextureObject;
class vtkUnsignedCharArray;

class APERTURERENDERING_EXPORT vtkApertureLightingMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkApertureLightingMapper* New();
  vtkTypeMacro(vtkApertureLightingMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LightingModels
  {
    STANDARD = 0,
    APERTURE = 1
  };
  enum IntersectionModes
  {
    EXACT = 0,
    SMOOTHSTEP = 1
  };
  enum LambertModes
  {
    CENTROID = 0,
    EXACT_CAP = 1
  };

  ///@{
  /** APERTURE (default) or STANDARD (VTK's lighting, times 2^Exposure). Rebuilds shaders. */
  vtkSetClampMacro(LightingModel, int, STANDARD, APERTURE);
  vtkGetMacro(LightingModel, int);
  ///@}

  ///@{
  /** Point arrays read by the APERTURE model (defaults "Normals", "BentNormal",
   *  "ApertureRadius"). Changing them re-uploads the geometry. */
  void SetNormalArrayName(const char* name);
  void SetBentNormalArrayName(const char* name);
  void SetApertureRadiusArrayName(const char* name);
  const char* GetNormalArrayName() const { return this->NormalName.c_str(); }
  const char* GetBentNormalArrayName() const { return this->BentName.c_str(); }
  const char* GetApertureRadiusArrayName() const { return this->RadiusName.c_str(); }
  ///@}

  ///@{
  /**
   * The sun: direction (towards it, any length > 0, normalised; in the mesh frame: see
   * vtkApertureSolarPosition::GetDirection), apparent angular radius in degrees, (0, 90]
   * (default 0.26667, SPA's mean), a scale widening it into a soft area light (finite, > 0;
   * default 1; the widened radius is clamped to [1e-6 rad, 90°]: below, a point sun), and its
   * irradiance normal to the beam in W/m² per RGB channel (finite, >= 0; default 1000, 1000,
   * 1000). Other values are refused.
   */
  void SetSunDirection(double x, double y, double z);
  void SetSunDirection(const double d[3]) { this->SetSunDirection(d[0], d[1], d[2]); }
  vtkGetVector3Macro(SunDirection, double);
  void SetSunAngularRadius(double degrees);
  double GetSunAngularRadius() const { return this->SunAngularRadius; }
  void SetSunScale(double scale);
  double GetSunScale() const { return this->SunScale; }
  void SetSunIrradiance(double r, double g, double b);
  vtkGetVector3Macro(SunIrradiance, double);
  ///@}

  /** Uniform sky radiance filling the aperture, W/m²/sr per RGB channel (finite, >= 0;
   *  default 30, 35, 45), used when there is no sky table. */
  void SetSkyRadiance(double r, double g, double b);

  /**
   * Fill each aperture with the sky model over that aperture instead: a table of the caps'
   * radiances weighted by the cosine to their axes (vtkApertureSolarPosition::ComputeSkyTable,
   * which says why; layout and trilinear lookup of
   * ap_light_sky_lookup), `azimuths` x `elevations` x `radii` RGB tuples, uploaded as a small
   * float texture (again only when the table or its MTime changes). nullptr: back to the
   * uniform SkyRadiance. Switching between a table and none compiles the other shader variant
   * (the geometry is not uploaded again); replacing one table by another, as when the sun moves,
   * does not. Wrong sizes are an error, and the previous sky (table or uniform) stays. The
   * table's values may change in place (Modified() uploads them); its size may not: a table
   * of other sizes at a draw or ComputeReference is an error there, and the uniform sky
   * replaces it (give a new size with SetSkyTable again).
   */
  void SetSkyTable(vtkFloatArray* table, int azimuths, int elevations, int radii);
  vtkFloatArray* GetSkyTable() { return this->SkyTable; }
  vtkGetVector3Macro(SkyRadiance, double);

  ///@{
  /**
   * EXACT (default) or SMOOTHSTEP cap intersection; CENTROID (default) or EXACT_CAP Lambert.
   * Each combination is a compiled shader variant: a change compiles (or takes from the
   * shader cache) the other variant at the next draw, without re-uploading the geometry.
   */
  void SetIntersectionMode(int mode);
  int GetIntersectionMode() const { return this->IntersectionMode; }
  void SetLambertMode(int mode);
  int GetLambertMode() const { return this->LambertMode; }
  ///@}

  ///@{
  /**
   * Exposure in EV: the radiance is scaled by 2^Exposure before tone mapping (default 0;
   * clamped to [-30, 30] without an error, NaN refused; negative values darken, as on a
   * camera). Tone mapping on (default): 1 − exp(−x) then sRGB encoding, for 8-bit display;
   * off: the exposed linear value (clipped at 1 by an 8-bit framebuffer).
   */
  void SetExposure(double ev);
  double GetExposure() const { return this->Exposure; }
  void SetToneMapping(bool on);
  bool GetToneMapping() const { return this->ToneMapping; }
  ///@}

  /**
   * The CPU reference of the APERTURE model (ap_light.h, double precision) with this mapper's
   * current parameters, at every point of `mesh` (which needs the three arrays) for a constant
   * albedo (RGB in [0, 1]): the outgoing radiance (W/m²/sr, 3 components, NaN at nodata) into
   * `radiance` and the displayed 8-bit colour (exposure, tone mapping, sRGB as the shader;
   * black at nodata) into `display`; either may be nullptr. False (GetInputProblem() says
   * why) if the arrays are missing or wrongly sized, or the albedo is outside [0, 1].
   */
  bool ComputeReference(vtkPolyData* mesh, const double albedo[3], vtkDoubleArray* radiance,
    vtkUnsignedCharArray* display);

  enum ShadingFrequencies
  {
    PER_FRAGMENT = 0,
    PER_VERTEX = 1
  };
  ///@{
  /**
   * Where the lighting model runs: PER_FRAGMENT (default: every pixel, from interpolated
   * normals, bent normals and aperture radii) or PER_VERTEX (at the vertices, the irradiance
   * interpolated across each triangle: faster when triangles are about pixel-sized, as for
   * large terrain meshes, and identical at the vertices; softer where triangles span many
   * pixels). Switching compiles the other shader variant (no geometry upload).
   */
  void SetShadingFrequency(int frequency);
  vtkGetMacro(ShadingFrequency, int);
  ///@}

  /** How many times the geometry (vertex buffers) has been uploaded to the GPU. */
  int GetGeometryUploads() const { return this->GeometryUploads; }

  /** Why the last check of the input failed ("" when the arrays are usable). */
  const char* GetInputProblem() const { return this->InputProblem.c_str(); }

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;

protected:
  vtkApertureLightingMapper();
  ~vtkApertureLightingMapper() override;

  void ReplaceShaderValues(
    std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceFinish(vtkRenderer* ren, vtkActor* act) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

  /** True when `mesh` (default: the input) has the APERTURE model's arrays; else
   *  InputProblem says why. */
  bool CheckInput(vtkPolyData* mesh = nullptr);
  /** Before a draw or a reference: a sky table whose array changed its size after
   *  SetSkyTable (a DeepCopy into it, a ComputeSkyTable of other sizes) is dropped, with an
   *  error, for the uniform SkyRadiance (its upload and lookups would read past it). */
  void DropResizedSkyTable(const char* where);
  /** Map the three arrays to the shader's vertex attributes, leaving others mapped (none of
   *  the three without the APERTURE model in use). */
  void MapArrays();
  /** Set one of the model's array names: remapped and re-uploaded when it changes. (Not
   *  named SetArrayName, which would hide vtkMapper's public one from C++ callers.) */
  void SetModelArrayName(std::string& field, const char* name);

  int LightingModel = APERTURE;
  std::string NormalName = "Normals";
  std::string BentName = "BentNormal";
  std::string RadiusName = "ApertureRadius";
  double SunDirection[3] = { 0.0, 0.0, 1.0 };
  double SunAngularRadius = 0.26667;
  double SunScale = 1.0;
  double SunIrradiance[3] = { 1000.0, 1000.0, 1000.0 };
  double SkyRadiance[3] = { 30.0, 35.0, 45.0 };
  int IntersectionMode = EXACT;
  int LambertMode = CENTROID;
  double Exposure = 0.0;
  bool ToneMapping = true;
  int ShadingFrequency = PER_FRAGMENT;
  int GeometryUploads = 0;
  std::string InputProblem;
  vtkFloatArray* SkyTable = nullptr;
  int SkyTableSize[3] = { 0, 0, 0 };
  vtkTextureObject* SkyTexture = nullptr;
  vtkMTimeType SkyTextureTime = 0;
  vtkTimeStamp VariantTime; // the last change of a compiled shader variant's choice
  bool UsingAperture = false; // the shaders in use were built for the APERTURE model
  bool DrewWithGeometryShader = false; // this render drew a program of VTK's geometry shader

private:
  vtkApertureLightingMapper(const vtkApertureLightingMapper&) = delete;
  void operator=(const vtkApertureLightingMapper&) = delete;
};

#endif
