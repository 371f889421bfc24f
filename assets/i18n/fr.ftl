# Le texte de l'application en français. Mêmes clés que en.ftl (les tests
# vérifient que les deux fichiers ont les mêmes clés et les mêmes variables).
# Les nombres arrivent déjà formatés, avec leur unité, et gardent le point
# décimal (les curseurs et les champs le lisent). Les formules restent telles
# quelles.

## Le menu des langues, les erreurs

menu-language = Langue
menu-language-tip = La langue du texte de l'application (la ligne de commande reste en anglais)
error-frame = Erreur : { $message }

## Top bar, status bar, panels (lab/panels.rs)

top-undo = Annuler
top-undo-tip = Annuler le dernier changement de réglage (Ctrl+Z)
top-redo = Rétablir
top-redo-tip = Rétablir (Ctrl+Maj+Z ou Ctrl+Y)
top-reset-view = Vue initiale
top-reset-view-tip = Ramène la caméra à la vue propre de la scène (R)
top-split = Comparer A | B
top-split-tip = Compare deux réglages côte à côte (S)
top-settings = Réglages
top-settings-tip = Affiche le panneau des réglages (F9 masque les deux panneaux)
top-analysis = Analyse
top-analysis-tip = Affiche le panneau de la sonde, de l'énergie, de la référence et des temps
top-help = Aide (F1)
top-help-tip = Raccourcis clavier et souris
status-hint = Glisser : orbite · Maj+glisser : déplacer · molette : zoom · clic : sonde · F1 : aide
status-impossible = Configuration impossible : { $first }
status-impossible-more =
    Configuration impossible : { $first } (+{ $more } { $more ->
        [one] autre
       *[other] autres
    })
status-impossible-tip =
    { $lines }
    Le GPU et la référence CPU ne concordent pas sur une telle configuration.
section-experiments = Expériences
section-scene = Scène
section-light = Lumière
section-material = Matériau
section-shadow = Ombres
section-view = Vue
section-files = Fichiers
section-probe = Sonde de pixel
section-energy = Énergie : albédo a(θ)
section-reference = Référence et erreur
section-timings = Temps de calcul
lobe-at-probe = au point sondé
lobe-at-centre = de la lumière au centre de la scène, n = +Y

## Desktop (lab/desktop.rs)

menu-file = Fichier

## Status lines (lab/apply.rs)

status-settings-saved = réglages enregistrés dans { $path }
status-exr-written = valeurs linéaires écrites dans { $path }
status-reset-everything = tout est réinitialisé (Ctrl+Z rend les réglages)
status-preset = expérience : { $preset } (Ctrl+Z pour annuler)
error-settings-scene-missing = sa scène « { $scene } » est introuvable
status-settings-loaded = réglages chargés depuis { $path } (Ctrl+Z pour annuler)
scene-built-in = intégrée
status-scene = scène : { $name }, { $triangles } triangles
status-scene-warnings =
    {" "}({ $count } { $count ->
        [one] avertissement
       *[other] avertissements
    } : { $warnings })
status-loading = chargement de { $path }…
error-cannot-start-loading = impossible de lancer le chargement : { $message }
error-no-image-to-export = pas encore d'image à exporter
error-image-changed-size = l'image a changé de taille pendant sa lecture ; réessayez

## Shadow panel (shadow.rs)

filter-none-tip = Un seul test de profondeur au texel le plus proche : V ∈ {"{"}0, 1{"}"}, bords durs et crénelés
filter-hw2x2-tip = L'échantillonneur de comparaison matériel : 2×2 tests de profondeur, pondérés bilinéairement
filter-pcf-tip = Percentage-closer filtering : V = moyenne de n×n tests de profondeur (flou, non physique)
filter-poisson-tip = Tests de profondeur sur un disque de Poisson tourné à chaque pixel : du bruit au lieu de bandes
filter-pcss-tip =
    Percentage-closer soft shadows : une recherche des bloqueurs estime la largeur de la pénombre
    w = R · (d_receveur − d_bloqueur) / d_bloqueur, puis filtre sur w
filter-vsm-tip = Carte d'ombres à variance : moments flous (μ, σ²), V ≤ σ² / (σ² + (d − μ)²) (Tchebychev)
filter-evsm-tip = VSM exponentielle : moments de e^(c·d), moins de fuites de lumière que VSM
filter-msm-tip = Carte d'ombres à moments : moments d, d², d³, d⁴, reconstruction de Hamburger (Peters & Klein 2015)
bias-auto-tip = Le plan tangent du receveur prédit sa profondeur en chaque texel, plus une petite marge
bias-constant-tip = d_comparée = d − D : trop peu donne de l'acné, trop donne du peter-panning (ombre détachée)
bias-slope-tip = d_comparée = d − (D + S · texel · tan θ) : plus de biais en lumière rasante
bias-normal-tip = Le point consulté se déplace de N empreintes de texel le long de la normale
shadow-enabled = Ombres
shadow-enabled-tip = L = f_r · E · V ; désactivées : V = 1 partout
shadow-filter = Filtre
shadow-filter-tip = Comment les tests de profondeur deviennent une visibilité V ∈ [0, 1]
shadow-kernel = Noyau
shadow-kernel-tip = n×n tests de profondeur espacés d'un texel
shadow-kernel-size-tip = V = moyenne de { $tests } tests de profondeur
shadow-samples = Échantillons
shadow-samples-tip = Tests de profondeur sur un disque de Poisson
shadow-samples-range-tip = { $help } (4 … 64) : davantage est plus lisse et plus lent
shadow-radius = rayon
shadow-radius-tip = Rayon du disque (texels de la carte d'ombres) : plus large est plus doux
unit-texels = {" "}texels
shadow-light-radius = R de la lumière
shadow-light-radius-tip =
    Le rayon R de la lumière (le même que dans le panneau Lumière) : la largeur de la pénombre est
    w = R · (d_receveur − d_bloqueur) / d_bloqueur. R = 0 donne des ombres dures.
shadow-blocker-samples = Échantillons bloqueurs
shadow-blocker-samples-tip = Tests de profondeur de la recherche des bloqueurs
shadow-filter-samples = Échantillons du filtre
shadow-filter-samples-tip = Tests de profondeur sur la pénombre estimée
shadow-blur = flou
shadow-blur-tip = Rayon du flou séparable des moments (texels)
shadow-bleed-reduction = réduction des fuites
shadow-bleed-reduction-tip = V' = clamp((V − b) / (1 − b), 0, 1) : coupe les fuites de lumière de Tchebychev
shadow-moment-bias = biais des moments α
shadow-moment-bias-tip = b' = (1 − α) b + α (½, ½, ½, ½) : α plus grand, plus de fuites de lumière, moins de bruit
shadow-resolution = Résolution
shadow-resolution-tip =
    Texels par côté de la carte d'ombres : un texel couvre (largeur du frustum / résolution)
    mètres ; trop peu de texels par pixel → crénelage (aliasing)
shadow-resolution-size-tip = { $side } × { $side } texels, { $mib } Mio de profondeur
shadow-adapter-limit-tip = Limite de l'adaptateur : { $side } texels par côté
shadow-resolution-used = { $used }² utilisée : { $why }
shadow-bias = Biais
shadow-bias-tip = Décale la profondeur comparée : acné (trop peu) contre peter-panning (trop)
shadow-bias-depth-tip = Décalage constant D de la profondeur vers la lumière (m)
shadow-bias-auto = d'après le plan du receveur et l'empreinte du texel
shadow-bias-slope-tip = Facteur de pente S : biais D + S · empreinte du texel · tan θ
shadow-bias-normal-tip = Décalage normal N : le point consulté se déplace de N empreintes de texel le long de n

## View panel (view.rs)

view-shaded-tip = Luminance réfléchie L = f_r · E · V (W/m²/sr), exposée et encodée en sRGB
view-depth-tip = La carte de profondeur de la lumière (distance normalisée à la lumière)
view-visibility-tip = V ∈ [0, 1] d'après la carte d'ombres : noir = à l'ombre, blanc = éclairé
view-ndotl-tip = cos θ = max(0, n·l) : noir à l'horizon, blanc face à la lumière
view-irradiance-tip = E · V = I cos θ / r² · V (W/m²), fausses couleurs
view-brdf-tip = f_r / c (1/sr), fausses couleurs, échelle logarithmique sur deux décades
view-diffuse-tip = La part diffuse c · k/π · E · V (W/m²/sr)
view-specular-tip = La part spéculaire c · (1 − k) N(m) cos^m θ_h · E · V (W/m²/sr)
view-texel-density-tip = Texels de la carte d'ombres par pixel de l'écran (log₂), rouge : agrandis et crénelés
view-frustum-tip = Le frustum de la lumière (ou les faces du cube) tracé sur l'image ombrée
view-ref-visibility-tip = La visibilité V_ref de la référence CPU (à calculer dans le panneau Référence)
view-error-tip = Erreur signée de luminance L − L_ref par rapport à la référence CPU (W/m²/sr)
view-show = Afficher
view-show-tip = Ce que montre l'image (V : vue suivante)
view-exposure = exposition
view-exposure-tip = Valeur affichée = L · 2^EV, puis la fonction de transfert sRGB (ombrée, diffuse, spéculaire)
split-enabled = Vue partagée A | B  (S)
split-enabled-tip =
    Les deux moitiés montrent les réglages courants ; B diffère de A par un seul réglage.
    Faites glisser la séparation pour passer de l'une à l'autre.
split-compare = Comparer
split-compare-tip = Le réglage qui diffère entre A et B
split-layout = Disposition
split-wipe = rideau
split-wipe-tip = Une image : A à gauche de la séparation, B à droite
split-side-by-side = côte à côte
split-side-by-side-tip = Deux images entières de la même vue, caméras liées : A à gauche, B à droite
split-divider = séparation
split-divider-tip = Où A finit et B commence (fraction de la largeur) ; ou faites glisser la ligne dans l'image

## Light panel (light.rs)

light-position = Position q
light-position-tip =
    Centre de la lumière (m). Faites glisser le repère jaune dans l'image :
    parallèlement à l'image, ou Ctrl+glisser pour la hauteur.
light-position-axis-tip = Position de la lumière, coordonnée { $axis } (m) ; +Y vers le haut
light-power = Flux Φ
light-power-tip = Flux énergétique émis dans toutes les directions (W)
light-power-slider-tip = Φ (W), multiplié par la couleur. I = Φ / 4π ; E = I cos θ / r²
light-intensity-tip = Intensité d'une source ponctuelle isotrope : flux par stéradian, I = Φ / 4π (W/sr)
light-radius = Rayon de la sphère R
light-radius-tip =
    R = 0 : une source ponctuelle (ombres dures). R > 0 : une sphère lumineuse de même flux
    (ombres douces avec le filtre PCSS).
light-radius-slider-tip = R (m) ; la luminance de la sphère est L_e = Φ / (4π² R²)
light-sphere-radiance-tip = Luminance uniforme de la surface de la sphère lumineuse (W/m²/sr)
light-point = source ponctuelle
light-colour = Couleur
light-colour-tip = Facteurs RVB linéaires qui multiplient Φ
light-colour-button-tip = Couleur de la lumière (RVB linéaire) : Φ_rvb = Φ · couleur
light-white = blanc
light-white-tip = Couleur (1, 1, 1)

## Material panel (material.rs)

norm-none-note = le lobe brut : l'énergie baisse quand m croît, et dépasse 1 aux petits m
norm-ndf-note = normalise le lobe sur les vecteurs médians, pas l'énergie réfléchie
norm-approx-note = l'approximation courante ; a(0°) > 1 aux petits m (1.075 à m = 8)
norm-exact-note = exacte en incidence normale : a(0°) = 1 pour tout m
material-use-scene = Utiliser les k et m de la scène
material-use-scene-tip =
    Activé : les objets dont le matériau glTF donne k et m les gardent ; les autres prennent
    les valeurs ci-dessous. Désactivé : tous les objets prennent les valeurs ci-dessous.
material-k = Part diffuse k
material-k-tip =
    k ∈ [0, 1] : 1 est du Lambert pur (f_r = c/π), 0 le lobe seul.
    { $brdf }
material-m = Exposant m
material-m-tip =
    Exposant de Blinn-Phong m ∈ [0, 10⁶] : plus grand donne un reflet plus net ; m = 0 est un lobe plat (0⁰ = 1).
    { $brdf }
material-norm = Normalisation N(m)
material-override = Imposer la couleur de base c
material-override-tip = Remplace la couleur c (RVB linéaire) de chaque objet dans la BRDF
material-colour-tip = c (RVB linéaire, chaque composante dans [0, 1])

## Widgets (widgets.rs)

slider-zero-tip = Met exactement 0 (un curseur logarithmique ne peut l'atteindre)
