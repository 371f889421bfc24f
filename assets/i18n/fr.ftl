# Le texte de l'application en français. Mêmes clés que en.ftl (les tests
# vérifient que les deux fichiers ont les mêmes clés et les mêmes variables).
# Les nombres arrivent déjà formatés, avec leur unité, et gardent le point
# décimal (les curseurs et les champs le lisent). Les formules restent telles
# quelles.

## Le menu des langues

menu-language = Langue
menu-language-tip = La langue du texte de l'application (la ligne de commande reste en anglais)

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
section-colour = Couleur
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
view-delta-e-tip = ΔE2000 par pixel entre le résultat spectral et le produit RVB, tous deux tels qu'affichés (L · 2^EV), dans CIE Lab avec le blanc de l'illuminant à Y = 1 (CIEDE2000, Sharma, Wu & Dalal 2005) : vers 1 à peine visible, 2.3 le seuil de discrimination (JND). Demande un illuminant spectral (panneau Couleur)
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

## Help: shortcuts and gestures (shortcuts.rs)

shortcut-help = cette aide
shortcut-redo = rétablir
shortcut-undo = annuler un changement de réglage
shortcut-save-settings = enregistrer le fichier de réglages
shortcut-open-scene = ouvrir un fichier glTF/GLB (boîte de dialogue)
shortcut-reset-view = revenir à la vue initiale
shortcut-frame-all = tout cadrer : le modèle remplit la vue
shortcut-auto-exposure = exposition automatique d'après l'image
shortcut-split = vue partagée A | B activée/désactivée
shortcut-previous-view = vue de débogage précédente
shortcut-next-view = vue de débogage suivante
shortcut-reference = calculer la référence CPU
shortcut-cancel = annuler la référence / fermer cette aide
shortcut-screenshot = enregistrer une capture d'écran
shortcut-panels = masquer/afficher les panneaux latéraux
gesture-left-drag = Glisser (bouton gauche)
gesture-left-drag-does = faire tourner la caméra autour de sa cible
gesture-pan = Maj + glisser / glisser (bouton du milieu)
gesture-pan-does = déplacer la vue
gesture-wheel = Molette
gesture-wheel-does = zoom
gesture-click = Clic
gesture-click-does = sonder le pixel (chaque terme de L = f_r · E · V)
gesture-double-click = Double-clic
gesture-double-click-does = tourner autour du point sous le curseur
gesture-drag-light = Glisser la lumière jaune
gesture-drag-light-does = déplacer la lumière parallèlement à l'image
gesture-ctrl-drag-light = Ctrl + glisser la lumière
gesture-ctrl-drag-light-does = monter ou descendre la lumière
shortcut-or = {" "}ou{" "}
help-title = Clavier et souris
help-footer = Chaque nombre a son unité ; survolez un réglage ou une valeur pour voir sa formule.

## Scene panel (scene_panel.rs)

scene-size = { $triangles } triangles · { $size } de diagonale
scene-size-tip = La diagonale de la boîte englobante du modèle : les longueurs du labo la suivent
scene-empty = rien à dessiner : le fichier n'a aucun triangle
scene-frame-all = Tout cadrer (F)
scene-frame-all-tip = Avance la caméra selon sa direction jusqu'à ce que le modèle remplisse la vue
scene-auto-exposure = Exposition auto (E)
scene-auto-exposure-tip = EV tel que le 95e centile de la luminance des pixels éclairés s'affiche à 0.8 (linéaire)
scene-cameras = Caméras du fichier :
scene-camera-tip = La caméra { $index } du fichier (--camera gltf:{ $index })
scene-file-light = Lumière du fichier « { $name } » : I = { $intensity }
scene-file-light-tip =
    KHR_lights_punctual donne des candelas ; I (W/sr) = I (cd) / { $efficacy } lm/W, l'efficacité
    d'une lumière à 555 nm (une source blanche émet plus de watts pour les mêmes candelas). La
    lumière du labo y démarre avec Φ = 4π I.
scene-ground = Sol
scene-ground-tip = Un sol qui reçoit les ombres au point le plus bas du modèle (--ground)
scene-ground-auto-tip = Sous un modèle qui n'en a pas
scene-ground-on-tip = Toujours
scene-ground-off-tip = Jamais : la géométrie du fichier seule
scene-ground-k = k du sol
scene-ground-k-tip = Le mélange diffus/spéculaire du sol : f_r = c (k/π + (1 − k) N(m) cos^m θ_h)
scene-ground-m = m du sol
scene-ground-m-tip = L'exposant de Blinn-Phong m du sol

## Energy panel (energy.rs)

energy-curve-tip = a(θ_i) = ∫ f_r(l, o) cos θ_o dω_o sur l'hémisphère, avec c = 1
energy-lecture-angles = angles du cours
energy-red-band = bande rouge : a(θ_i) > 1, la BRDF crée de l'énergie
energy-albedo-tip = Albédo directionnel ; rouge au-dessus de 1 : la BRDF réfléchit plus qu'elle ne reçoit
energy-default-incidence = 45° par défaut
energy-lobe = Lobe dans le plan d'incidence, θ_i = { $theta }° ({ $source })
energy-lobe-tip = Rayon : f_r / c (1/sr) vers chaque direction sortante θ_o ; n pointe vers le haut
energy-light-l = lumière l
energy-normal-n = normale n
energy-surface = surface
energy-peak = pic f_r / c = { $peak } 1/sr

## Reference panel (reference.rs)

reference-cannot-start = impossible de lancer le fil de la référence : { $message }
reference-cancelled = référence annulée
reference-stopped = le fil de la référence s'est arrêté sans résultat
reference-compute = Calculer la référence (F5)
reference-compute-tip =
    Lance des rayons sur la vue courante, sur le CPU en f64 (un fil en arrière-plan) : les L et V
    exacts que la carte d'ombres approche
reference-cancel = Annuler (Échap)
reference-cancel-tip = Arrête le calcul
reference-progress-tip = { $done } pixels sur { $total }
reference-none = Pas encore de référence : les vues erreur et visibilité de référence en ont besoin.
reference-done = { $width }×{ $height } en { $seconds } s
reference-stale = PÉRIMÉE : la vue, la lumière, le matériau ou la taille ont changé depuis ; recalculez
reference-rmse-tip = √(moyenne sur les pixels couverts de (L − L_ref)²), luminance
reference-relative = relative
reference-max-error = max |erreur|
reference-pixels = pixels
reference-pixels-tip = Pixels couverts par la scène
reference-rmse-in-error-view = RMSE : affichée dans la vue erreur
reference-error-view = Vue erreur
reference-error-view-tip = L − L_ref signée en fausses couleurs
reference-visibility = V de référence
reference-visibility-tip = La visibilité V_ref de la référence

## Pixel probe (probe.rs)

probe-p-tip = Là où le rayon du pixel rencontre la surface (m)
probe-n-tip = Normale unitaire d'ombrage (normales des sommets interpolées)
probe-l-tip = l = (q − p) / r, direction unitaire vers la lumière
probe-r-tip = r = |q − p|, distance au centre de la lumière (m)
probe-cos-tip = cos θ = n·l ; négatif : la lumière est sous l'horizon
probe-e-tip = E = I · max(0, cos θ) / r² (W/m²) ; une sphère lumineuse à cheval sur l'horizon utilise sa forme exacte
probe-c-tip = La couleur c de la BRDF (RVB linéaire) : couleur de base × texture aux uv du point touché, ou la couleur imposée
probe-v-map-tip = Visibilité d'après la carte d'ombres avec le filtre et le biais courants, V ∈ [0, 1]
probe-texels-tip = Texels de la carte d'ombres par pixel de l'écran : sous 1 la carte est agrandie (crénelage)
probe-l-value-tip = L = f_r · E · V · couleur de la lumière (W/m²/sr), en f64 avec le V du GPU
probe-l-gpu-tip = La luminance du moteur de rendu en ce pixel (f32)
probe-reading-tip = Lecture de la cible auxiliaire du moteur de rendu
probe-unshadowed-tip = L / V = f_r · E · couleur de la lumière
probe-v-traced-tip = Visibilité de la lumière depuis p, par lancer de rayons sur le CPU en f64 : le V exact que la carte d'ombres approche
probe-l-traced-tip = La luminance de la référence CPU au centre de ce pixel
probe-l-image-tip = L'image de référence calculée en ce pixel (F5), à laquelle la vue erreur se compare
probe-v-map = V (carte d'ombres)
probe-texels = texels/pixel
probe-l-gpu = L (GPU)
probe-v-traced = V (lancer de rayons)
probe-l-traced = L (lancer de rayons)
probe-l-image = L (image de référence)
probe-o-tip = Direction unitaire vers l'œil
probe-stale = {"  "}(périmée)
probe-hint = Cliquez un pixel de l'image pour y voir chaque terme de L = f_r · E · V.
probe-pixel = pixel ({ $x }, { $y }) sur { $width }×{ $height }, moitié { $half }
probe-background = fond : le rayon du pixel ne rencontre aucune surface
probe-object = { $object } — matériau { $material }

## Files: menu, panel, dialogs (files.rs)

dialog-open-scene = Ouvrir une scène glTF/GLB
dialog-load-settings = Charger un fichier de réglages TOML
dialog-save-settings = Enregistrer les réglages en TOML
dialog-screenshot = Enregistrer une capture d'écran (PNG)
dialog-export-exr = Exporter la luminance linéaire (EXR)
files-open-scene-dialog = Ouvrir une scène…
files-open-scene-dialog-tip = Un fichier .gltf ou .glb (Ctrl+O ; ou déposez-le sur la fenêtre)
files-built-in = Scène intégrée
files-built-in-tip = Retour à la scène propre du labo
files-load-settings-dialog = Charger des réglages…
files-load-settings-dialog-tip = Un fichier de réglages TOML, tel que le lit `lumlab render --settings FILE`
files-save-settings = Enregistrer les réglages
files-save-settings-tip = Écrit tous les réglages dans le dernier fichier de réglages utilisé (Ctrl+S)
files-save-settings-as = Enregistrer les réglages sous…
files-save-settings-as-tip = Écrit tous les réglages dans un nouveau fichier TOML
files-screenshot-dialog = Enregistrer une capture…
files-screenshot-dialog-tip = Toute la fenêtre en PNG
files-export-exr-dialog = Exporter en EXR…
files-export-exr-dialog-tip = Les valeurs linéaires de la moitié A, sans exposition ni sRGB
files-browse = Parcourir…
files-browse-tip = Choisir un fichier .gltf/.glb et l'ouvrir (Ctrl+O)
files-open-scene = Ouvrir la scène
files-open-scene-tip = Rouvre le fichier affiché
files-kind-settings = Réglages
files-save = Enregistrer (Ctrl+S)
files-save-tip = Écrit tous les réglages dans le fichier affiché
files-load = Charger
files-load-tip = Lit les réglages du fichier affiché (Ctrl+Z pour annuler)
files-save-as = Enregistrer sous…
files-save-as-tip = Écrit les réglages dans un autre fichier TOML
files-load-dialog = Charger…
files-load-dialog-tip = Choisir un fichier de réglages TOML et le charger
files-screenshot = Enregistrer une capture (F12)
files-screenshot-tip = Toute la fenêtre, telle qu'affichée, dans le fichier affiché
files-screenshot-as-tip = Toute la fenêtre, dans un fichier PNG de votre choix
files-export-exr = Exporter en EXR
files-export-exr-tip = Les valeurs linéaires brutes de la moitié A (luminance L en W/m²/sr pour `shaded`) dans le fichier affiché
files-export-as = Exporter sous…
files-export-as-tip = La même chose, dans un fichier EXR de votre choix
replace-title = Remplacer le fichier ?
replace-exists = « { $path } » existe déjà.
replace-replace = Remplacer
replace-cancel = Annuler
files-scene = Scène : { $name }
files-reset-everything = Tout réinitialiser
files-reset-everything-tip =
    Tous les réglages, la vue partagée, les panneaux et la scène reviennent à leurs valeurs par défaut
    (Ctrl+Z rend les réglages)
files-none = (aucun)

## Toasts (toast.rs)

toast-dismiss = Fermer

## Recent files (recent.rs)

recent-scenes = Scènes récentes
recent-settings = Réglages récents
recent-none = (aucun pour l'instant)
recent-missing = { $name } (introuvable)
