/* preset_builtin: the shipped presets.  Each is INI text in the preset file
 * format; comments give each value's source.  `skinbake preset cat NAME`
 * prints one as a starting point for own presets. */
#include "config.h"
#include "skin/preset_builtin.h"

/* Li & Ng, "Rendering human skin using a multi-layer reflection model"
 * (../shared/paper), read as ../shared/paper/README.md says: Table 1 is the
 * epidermal mu_a, Table 2 the dermal mu_a and "scattering coefficient" at
 * 470, 550 and 656 nm (Table 2 prints 656 as "56").  Table 2's scattering row
 * (60, 37, 23 /cm) is Jacques 1998's reduced scattering mu_s' = 2e5 wl^-1.5 +
 * 2e12 wl^-4 (60.6, 37.4, 22.7), so `paper` uses mu_s = mu_s' / (1 - g) and
 * `paper-literal` the printed numbers as mu_s.  The epidermis scatters "close
 * to the dermis" (section 4), so it gets the dermis's mu_s.  Choices where
 * the paper gives a range or nothing: g 0.8 (paper: 0.7-0.95), epidermis
 * 0.1 mm (paper: "at maximum 1 mm", the thinnest layer), n 1.43 for every
 * tissue layer (paper: 1.37-1.5, all equal; its Fresnel figure uses 1.43),
 * sebum 10 um (paper: "thin"; a clear film's thickness has no effect in a
 * plane-parallel model), roughness (the paper's surface is smooth; the
 * analytic lobe needs one).  docs/presets.md has the table with sources. */
#define PAPER_HEAD \
	"[skin]\n" \
	"model = tables\n" \
	"wavelengths = 470, 550, 656   ; Tables 1-2; Table 2 prints 656 nm as \"56\"\n" \
	"[sebum]\n" \
	"thickness = 0.001   ; 10 um: the paper says only \"thin sebum layer\" (our choice)\n" \
	"n = 1.5             ; section 4: \"it is assigned a value of 1.5\"\n" \
	"[epidermis]\n" \
	"thickness = 0.01    ; 0.1 mm: section 4, \"thinnest layer ... at maximum 1 mm\" (our choice)\n" \
	"n = 1.43            ; section 4: 1.37-1.5, all layers equal; Figure 1 uses 1.43\n" \
	"g = 0.8             ; section 4: g typically 0.7-0.95 (our choice in that range)\n" \
	"[dermis]\n" \
	"thickness = 0.25    ; section 4: \"approximately 2.5 mm thick\"; index-matched below\n" \
	"n = 1.43            ; as the epidermis (\"the same refractive index\")\n" \
	"g = 0.8             ; as the epidermis\n" \
	"[surface]\n" \
	"roughness_skin = 0.35   ; not in the paper (smooth surface): Donner & Jensen 2006 m, as GGX alpha\n" \
	"roughness_sebum = 0.25  ; not in the paper: assumed, the film smooths the micro-relief\n"

/* mu_a: Table 1 (epidermis), Table 2 (dermis).  mu_s: Table 2's row read as
 * mu_s' / (1 - 0.8) (paper) or as printed (paper-literal), both layers. */
#define PAPER_INI \
	PAPER_HEAD \
	"[override.470]\n" \
	"epidermis.mua = 85   ; Table 1\n" \
	"epidermis.mus = 300  ; Table 2 mu_s' 60 / (1 - 0.8); epidermis \"close to the dermis\"\n" \
	"dermis.mua = 6       ; Table 2\n" \
	"dermis.mus = 300     ; Table 2 mu_s' 60 / (1 - 0.8)\n" \
	"[override.550]\n" \
	"epidermis.mua = 50   ; Table 1\n" \
	"epidermis.mus = 185  ; Table 2 mu_s' 37 / (1 - 0.8)\n" \
	"dermis.mua = 7       ; Table 2\n" \
	"dermis.mus = 185     ; Table 2 mu_s' 37 / (1 - 0.8)\n" \
	"[override.656]\n" \
	"epidermis.mua = 28   ; Table 1\n" \
	"epidermis.mus = 115  ; Table 2 mu_s' 23 / (1 - 0.8)\n" \
	"dermis.mua = 0.58    ; Table 2 (column printed \"56\")\n" \
	"dermis.mus = 115     ; Table 2 mu_s' 23 / (1 - 0.8)\n"

#define PAPER_LITERAL_INI \
	PAPER_HEAD \
	"[override.470]\n" \
	"epidermis.mua = 85   ; Table 1\n" \
	"epidermis.mus = 60   ; Table 2 as printed; epidermis \"close to the dermis\"\n" \
	"dermis.mua = 6       ; Table 2\n" \
	"dermis.mus = 60      ; Table 2 as printed\n" \
	"[override.550]\n" \
	"epidermis.mua = 50   ; Table 1\n" \
	"epidermis.mus = 37   ; Table 2 as printed\n" \
	"dermis.mua = 7       ; Table 2\n" \
	"dermis.mus = 37      ; Table 2 as printed\n" \
	"[override.656]\n" \
	"epidermis.mua = 28   ; Table 1\n" \
	"epidermis.mus = 23   ; Table 2 as printed\n" \
	"dermis.mua = 0.58    ; Table 2 (column printed \"56\")\n" \
	"dermis.mus = 23      ; Table 2 as printed\n"

/* The project's reference skin stack (`paper` before the paper's tables were
 * available; tests and benchmarks that compare with tests/data/public_refs.tsv use it):
 * - 550 nm: tests/data/public_refs.tsv AD_skin3 (epidermis albedo 370/420, optical
 *   thickness 4.2; dermis albedo 370/377, optical thickness 94.25; g 0.8,
 *   n 1.4; sebum n 1.5).
 * - 470 and 656 nm: the 550 nm values carried to those wavelengths with this
 *   program's chromophore model: epidermal mu_a as melanin (Jacques 1998,
 *   fraction 0.1003 fitted to 50/cm at 550) plus baseline; dermal mu_a as blood
 *   (S = 0.75, fraction 0.02683 fitted to 7/cm at 550) plus baseline; mu_s as
 *   370 (wl/550)^-b with Salomatina fits b = 1.322 (epidermis), 1.482 (dermis). */
#define REFSTACK_INI \
	"[skin]\n" \
	"model = tables\n" \
	"wavelengths = 470, 550, 656\n" \
	"[sebum]\n" \
	"thickness = 0.001   ; 10 um, reference stack (../shared/refs AD_skin3)\n" \
	"n = 1.5\n" \
	"[epidermis]\n" \
	"thickness = 0.01    ; 100 um, reference stack\n" \
	"n = 1.4\n" \
	"g = 0.8\n" \
	"[dermis]\n" \
	"thickness = 0.25    ; 2.5 mm, reference stack; index-matched below\n" \
	"n = 1.4\n" \
	"g = 0.8\n" \
	"[surface]\n" \
	"roughness_skin = 0.35   ; Beckmann m of Donner & Jensen 2006, taken as GGX alpha\n" \
	"roughness_sebum = 0.25  ; assumed: the film smooths the micro-relief\n" \
	"[override.470]\n" \
	"epidermis.mua = 84.6\n" \
	"epidermis.mus = 456\n" \
	"dermis.mua = 5.10\n" \
	"dermis.mus = 467\n" \
	"[override.550]\n" \
	"epidermis.mua = 50\n" \
	"epidermis.mus = 370\n" \
	"dermis.mua = 7\n" \
	"dermis.mus = 370\n" \
	"[override.656]\n" \
	"epidermis.mua = 27.8\n" \
	"epidermis.mus = 293\n" \
	"dermis.mua = 0.439\n" \
	"dermis.mus = 285\n"

/* Physiological presets (chromophore model).  Melanin, eumelanin share and
 * blood per Fitzpatrick type start from ../shared/skin_data/presets_skin_types.tsv
 * and are calibrated (scripts/calibrate-presets.sh) so the simulated colour
 * lies in the measured ranges (docs/presets.md).  Oily: a 5 um sebum film;
 * dry: no film, rougher surface. */
#define PHYS_INI(MEL, EU, BLOOD) \
	"[skin]\n" \
	"model = chromophores\n" \
	"wavelengths = 400:700:20\n" \
	"[sebum]\n" \
	"thickness = 0.0005  ; 5 um oily film (skin-optics.md A2.8: about 1-10 um)\n" \
	"n = 1.5             ; Li & Ng; squalene about 1.49\n" \
	"[epidermis]\n" \
	"thickness = 0.006   ; 60 um, the thickness Jacques 2013 uses with melanin fractions\n" \
	"n = ding2006\n" \
	"g = vangemert1989\n" \
	"melanin = " MEL "\n" \
	"eumelanin = " EU "\n" \
	"musp500 = 69.0      ; Mie + Rayleigh fit to Salomatina 2006 epidermis\n" \
	"musp_power = 0.58\n" \
	"musp_rayleigh = 0.37\n" \
	"[dermis]\n" \
	"thickness = 0.2     ; 2 mm (skin-optics.md A2.8: 1-4 mm)\n" \
	"n = ding2006\n" \
	"g = vangemert1989\n" \
	"blood = " BLOOD "\n" \
	"so2 = 0.75          ; Donner & Jensen 2006, BioSpec\n" \
	"musp500 = 45.6      ; Mie + Rayleigh fit to Salomatina 2006 dermis\n" \
	"musp_power = 0.52\n" \
	"musp_rayleigh = 0.46\n" \
	"[subcutis]\n" \
	"thickness = inf     ; fat below the dermis (Meglinski & Matcher 2002 n, g, blood)\n" \
	"n = 1.44\n" \
	"g = 0.75\n" \
	"blood = 0.05\n" \
	"so2 = 0.75\n" \
	"musp500 = 35.0      ; fit to Salomatina 2006 hypodermis\n" \
	"musp_power = 1.136\n" \
	"[surface]\n" \
	"roughness_skin = 0.35   ; Beckmann m of Donner & Jensen 2006, taken as GGX alpha\n" \
	"roughness_sebum = 0.25  ; assumed: the film smooths the micro-relief\n"

#define DRY_INI(BASE) \
	"[skin]\n" \
	"base = " BASE "\n" \
	"[sebum]\n" \
	"thickness = 0       ; dry: no surface lipid film\n" \
	"[surface]\n" \
	"roughness_skin = 0.4    ; dry: a little rougher than the D&J 0.35 (assumed)\n"

/* Fitted to CUReT sample 39 (Dana et al. 1999) by scripts/fit-curet.py
 * (make fit-curet) on the 20 points at incidence 11.25 and 33.75 deg only,
 * with the adding-doubling solver (deterministic; record in
 * docs/validation/fit-curet39.tsv, method in docs/presets.md).  The
 * physiological model of medium-oily with five free parameters within
 * physiological bounds: melanin, blood (at its bound, 7 %), one scale on the
 * epidermal and dermal mu_s' (1.08), the sebum film (on; off: 6.67 % against
 * 6.35 % RMS) and the GGX roughness.  Training error 6.35 % RMS; held-out
 * error and why it is much larger: docs/validation.md 3.3. */
#define CURET39_INI \
	"[skin]\n" \
	"base = medium-oily   ; physiological model, 5 um sebum, medium skin's other values\n" \
	"[sebum]\n" \
	"thickness = 0.0005   ; fitted: film on (a clear film's thickness does not matter)\n" \
	"[epidermis]\n" \
	"melanin = 0.00074    ; fitted to CUReT 39 (bounds 0.0005-0.43)\n" \
	"musp500 = 74.5       ; fitted: 1.080 x the Salomatina fit 69.0\n" \
	"[dermis]\n" \
	"blood = 0.069        ; fitted, at its bound 0.07 (Jacques 2013: 0.2-7 %)\n" \
	"musp500 = 49.2       ; fitted: 1.080 x the Salomatina fit 45.6\n" \
	"[surface]\n" \
	"roughness_skin = 0.47   ; fitted (one roughness for skin and sebum)\n" \
	"roughness_sebum = 0.47  ; fitted\n"

const struct builtin_preset builtin_presets[] = {
	{ "paper", "Li & Ng Tables 1-2 at 470/550/656 nm, scattering read as mu_s', sebum n 1.5 (docs/presets.md)", PAPER_INI },
	{ "paper-dry", "the paper preset without sebum",
	  "[skin]\nbase = paper\n[sebum]\nthickness = 0   ; no sebum film (the paper's Figure 6(a))\n" },
	{ "paper-literal", "Li & Ng Tables 1-2 with the scattering row read literally as mu_s", PAPER_LITERAL_INI },
	{ "curet39", "fitted to CUReT sample 39 (incidence 11.25 and 33.75 deg): 5 um sebum, GGX 0.47, blood 7 %", CURET39_INI },
	{ "refstack", "the reference skin stack (tests/data/public_refs.tsv, AD_skin3) at 550 nm "
	  "(paper before issue 16)", REFSTACK_INI },
	{ "very-fair-oily", "Fitzpatrick I, very light (ITA > 55), 5 um sebum film", PHYS_INI("0.0015", "0.5", "0.02") },
	{ "very-fair-dry", "Fitzpatrick I, very light (ITA > 55), no sebum", DRY_INI("very-fair-oily") },
	{ "fair-oily", "Fitzpatrick II, light (ITA 41..55), 5 um sebum film", PHYS_INI("0.011", "0.6", "0.02") },
	{ "fair-dry", "Fitzpatrick II, light (ITA 41..55), no sebum", DRY_INI("fair-oily") },
	{ "medium-oily", "Fitzpatrick III, intermediate (ITA 28..41), 5 um sebum film", PHYS_INI("0.025", "0.7", "0.02") },
	{ "medium-dry", "Fitzpatrick III, intermediate (ITA 28..41), no sebum", DRY_INI("medium-oily") },
	{ "olive-oily", "Fitzpatrick IV, tan (ITA 10..28), 5 um sebum film", PHYS_INI("0.045", "0.8", "0.02") },
	{ "olive-dry", "Fitzpatrick IV, tan (ITA 10..28), no sebum", DRY_INI("olive-oily") },
	{ "brown-oily", "Fitzpatrick V, brown (ITA -30..10), 5 um sebum film", PHYS_INI("0.10", "0.9", "0.02") },
	{ "brown-dry", "Fitzpatrick V, brown (ITA -30..10), no sebum", DRY_INI("brown-oily") },
	{ "dark-oily", "Fitzpatrick VI, dark (ITA < -30), 5 um sebum film", PHYS_INI("0.16", "1.0", "0.02") },
	{ "dark-dry", "Fitzpatrick VI, dark (ITA < -30), no sebum", DRY_INI("dark-oily") },
};

const int builtin_preset_count = (int)(sizeof builtin_presets / sizeof builtin_presets[0]);
