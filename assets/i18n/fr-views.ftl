# Le texte de l'application en français, second fichier : la vue, le cours,
# les temps, la couleur et la visite. Mêmes règles que fr.ftl ; lu après lui.

## Viewport (viewport.rs)

viewport-gizmo-tip =
    Lumière en ({ $x }, { $y }, { $z }) m
    Glisser : déplacer parallèlement à l'image
    Ctrl+glisser : monter ou descendre
viewport-divider-tip = Glisser pour déplacer la séparation entre A et B
viewport-no-gpu = pas de moteur de rendu GPU
viewport-light-off-image = lumière (hors de l'image)
viewport-light-behind = lumière derrière la caméra

## Legends (legend.rs)

legend-visibility = visibilité V (0 = à l'ombre, 1 = éclairé)
legend-ref-visibility = visibilité de référence V_ref
legend-depth = carte de profondeur de la lumière (distance linéaire)
legend-near = proche
legend-far = loin
legend-delta-e = ΔE2000, produit RVB / spectral (1 : visible, 2.3 : JND)
legend-delta-e-needs-illuminant = ΔE demande un illuminant spectral : choisissez-en un dans le panneau Couleur (en mode RVB les deux modèles coïncident)

## Background jobs (lab/jobs.rs)

status-reference-ready = référence CPU prête : la vue erreur s'y compare
error-scene-kept = { $message } ; la scène actuelle est conservée
status-exposure-no-image = exposition auto : pas encore d'image
status-exposure = exposition auto : { $ev } EV (Ctrl+Z pour annuler)
status-exposure-nothing-lit = exposition auto : rien d'éclairé dans l'image
status-screenshot-saved = capture enregistrée dans { $path }

## Over the image (lab/image.rs)

image-rmse = RMSE = { $rmse } ({ $percent } % de la moyenne de L_ref)
image-nothing-to-draw = rien à dessiner
image-reference-running = Calcul de la référence CPU…
image-reference-none = Pas encore de référence CPU : appuyez sur F5 (panneau Référence)
image-reference-stale = La référence est PÉRIMÉE : réglages ou taille modifiés depuis (F5 la recalcule)

## Start-up (lab.rs)

error-showing-built-in = { $message } ; affichage de la scène intégrée

## Experiments (names.rs)

preset-shadow-acne = Acné d'ombre
preset-peter-panning = Peter-panning
preset-aliasing = Crénelage (aliasing)
preset-pcf-smoothing = Lissage PCF
preset-penumbra = Pénombre (sphère lumineuse)
preset-energy-gain = Gain d'énergie (sans normalisation)
preset-grazing = Incidence rasante
preset-shadow-acne-tip =
    Aucun biais de profondeur (constant, D = 0 m), aucun filtre, carte 1024². Chaque surface éclairée
    compare sa profondeur à sa propre copie quantifiée et s'ombre elle-même en bandes.
preset-peter-panning-tip =
    Biais constant D = 0.5 m, PCF 3×3, lumière en (3.5, 3, 3), une caméra près de la base de la boîte.
    Trop de biais : l'ombre se détache de l'objet qui la projette.
preset-aliasing-tip =
    Carte d'ombres 256², aucun filtre, biais automatique : un texel de la carte couvre de nombreux
    pixels, les bords des ombres montrent des marches d'escalier.
preset-pcf-smoothing-tip =
    La même carte 256² avec un filtrage PCF 7×7 : la moyenne de 49 tests de profondeur
    change les marches en un bord adouci.
preset-penumbra-tip =
    Sphère lumineuse R = 0.4 m en (2.5, 4, 2), PCSS avec 32 échantillons de recherche des bloqueurs et 32
    de filtrage, carte 2048² : la pénombre s'élargit avec la distance à l'occultant.
preset-energy-gain-tip =
    N(m) = 1 à m = 1, k = 0 sur chaque objet : a(0°) ≈ 2.86 > 1, la BRDF crée de
    l'énergie. Comparez avec la normalisation approchée ou exacte.
preset-grazing-tip =
    Lumière basse en (6, 0.8, 0), 2000 W, vue n·l : E = I cos θ / r² tombe à zéro quand
    la lumière atteint l'horizon.

## Lecture panel (lecture.rs)
top-lecture = Cours
top-lecture-tip = Affiche la visite guidée du cours (lumlab --tour)
lecture-no-steps = La visite n'a aucune étape.
lecture-previous = ◀ Précédent
lecture-next = Suivant ▶
lecture-steps = Étapes
lecture-close = Fermer
lecture-observe = À observer :
lecture-question = Question :

## Visibility (visibility.rs)
visibility-shadow-map-tip = Carte d'ombres : profondeur vue de la lumière, puis un test de profondeur filtré par pixel (rapide, approché)
visibility-ray-traced-tip = Lancer de rayons sur le GPU à travers un BVH : un rayon d'ombre de p vers la lumière. Lumière ponctuelle : V ∈ {"{"}0, 1{"}"} exact. Lumière sphérique : V = Σ V_i cos θ_i / Σ cos θ_i sur S directions de son cône par image, les suivantes d'une suite à faible discrépance propre au pixel, moyennées sur les images tant que rien ne change : N images font un seul ensemble bien réparti de N·S directions
visibility-label = Visibilité
visibility-label-tip = D'où vient V(p, q) ∈ [0, 1] : L = f_r · E · V
visibility-rays = rayons / image
visibility-rays-tip = S : rayons d'ombre par pixel et par image vers une lumière sphérique, les S points suivants d'une suite à faible discrépance (R2) sur son angle solide, tracés quatre par parcours du BVH (huit à partir de S = 8) ; une lumière ponctuelle n'en demande qu'un. Pendant un glissement, chaque image n'en envoie qu'un (l'image fixe qui suit en envoie de nouveau S et recommence sa moyenne)
visibility-frames = images
visibility-frames-tip = N : images moyennées tant que rien ne change sous une lumière sphérique ; le bruit de V décroît au moins en 1/√(N·S), plus vite grâce à la suite à faible discrépance (l'étiquette de la vue donne le bruit mesuré sur l'image, en comparant la moyenne de N images à celle de ses N/2 premières), puis l'image reste fixe. Une lumière ponctuelle est exacte dès la première image
visibility-noise-target = arrêt sous un bruit de
visibility-noise-target-tip = Le labo cesse d'ajouter des images avant N dès que le bruit mesuré sur l'image (le « bruit ≈ … % de la moyenne » de l'étiquette) ne dépasse plus cette part de la moyenne ; 0 : jamais, la moyenne va jusqu'à N images. Les 0,1 % par défaut sont moins d'un dixième d'un pas d'affichage 8 bits à mi-gris : l'image ne change plus à l'écran et les cœurs d'un adaptateur logiciel se reposent (sur la scène par défaut sous R = 0,3 m, 32 images de 8 rayons, quelque 6 s sur un adaptateur logiciel, au lieu de 256 images). Ce seuil change le moment où l'image se fige, pas son contenu : un nouveau seuil poursuit la même moyenne. Le --accumulate N de la ligne de commande et le rapport rendent toujours leurs N images
visibility-elapsed = après { $seconds } s
visibility-held = figée : sous { $target } %
visibility-exact = exact
visibility-noise-estimate = bruit ≈ { $percent } % de la moyenne
visibility-accumulation = { $frames } / { $max } images × { $rays } { $rays ->
        [one] rayon
       *[other] rayons
    }, { $noise }
probe-v-gpu-traced = V (lancer de rayons GPU)
probe-v-gpu-traced-tip = Visibilité tracée sur le GPU en f32 à travers le BVH : exacte pour une lumière ponctuelle, moyenne des échantillons des images accumulées pour une lumière sphérique
probe-xyz-tip = XYZ CIE 1931 de L (sRGB linéaire → XYZ, IEC 61966-2-1) ; sous une lumière spectrale, la référence a intégré S(λ) R(λ) contre x̄, ȳ, z̄
probe-delta-e-tip = ΔE2000 entre le résultat spectral et le produit RVB en ce pixel (L · 2^EV dans CIE Lab, le blanc de l'illuminant à Y = 1) : sous 1 invisible, au-dessus de 3 une autre couleur
probe-delta-e-gpu = ΔE2000 (vue GPU)
probe-delta-e-gpu-tip = La valeur de la vue delta-e en ce pixel : les deux modèles de couleur ombrés par le GPU en f32, CIEDE2000 en WGSL (shaders/delta_e.wgsl) ; elle doit égaler le ΔE2000 ci-dessus, tracé en f64

## Timings panel (timings.rs)

timings-render-scale = échelle de rendu
timings-dragging = (glissement en cours)
timings-full = (pleine)
timings-map-scale = , carte d'ombre { $percent } %
timings-render-scale-tip = Côté de l'image rendue / côté de la vue. Pendant un glissement, s = s_measured · √(budget / t_passes), budget de { $budget } ms pour { $fps } images/s, arrondi au palier de √2 inférieur (25, 35, 50, 71, 100 % ; un palier de plus seulement avec 10 % de marge), au moins { $min } %. Le côté de la carte d'ombre suit s ; à { $min } %, une carte qui coûte plus que ce que l'image laisse du budget rétrécit seule, jusqu'à { $map_min } % de son côté (sans viser moins de la moitié du coût propre de l'image). Pleine résolution dès la fin du glissement
timings-drag-fps = images/s (glissement)
timings-drag-fps-tip = Images rendues par seconde pendant le dernier glissement : 1 / (temps entre deux images), lissé
timings-drag-device = glissement
timings-drag-device-own = périph. propre
timings-drag-device-window = périph. fenêtre
timings-drag-device-tip = Sur un adaptateur logiciel (lavapipe, llvmpipe), les images d'un glissement sont rendues sur un second périphérique, dans un fil d'exécution à part, pendant que la fenêtre peint la dernière image revenue ; sur un GPU, sur le périphérique de la fenêtre (--drag-device auto|same|own)
timings-drag-meshes = maillages (glissement)
timings-drag-meshes-simplified = simplifiés, { $drawn } k / { $full } k triangles (carte d'ombre { $casters } k)
timings-drag-meshes-building = complets (simplification…)
timings-drag-meshes-full = complets
timings-drag-meshes-tip = Sur une scène de plus de { $threshold } k triangles, les images d'un glissement dessinent une copie simplifiée de chaque maillage (construite une fois par scène dans un fil d'exécution à part ; bords et coutures gardés), et leur carte d'ombre une copie plus grossière, soudée le long des coutures puisque la profondeur n'a pas besoin des normales ; en visibilité par lancer de rayons, leurs rayons d'ombre rencontrent la copie simplifiée qu'elles dessinent, à travers un BVH qui lui est propre : une approximation montrée seulement pendant le glissement. Les images fixes, la sonde, les statistiques d'erreur, la référence et les images exportées utilisent toujours les maillages complets
timings-ui-pass = passe d'interface
timings-ui-pass-tip = Temps CPU de la dernière image de l'interface, appels de rendu compris
timings-since-previous = depuis la précédente
timings-since-previous-tip = Temps entre les deux dernières images ; le labo ne redessine que lorsque quelque chose change
timings-half-a = Moitié A
timings-half-b = Moitié B
timings-render-tip = Temps CPU pour encoder et soumettre l'image
timings-shadow = ombres
timings-shadow-reused = réutilisée (dernier tracé { $time })
timings-shadow-tip = GPU : tracé de la carte de profondeur vue de la lumière (toutes les couches) ; une carte réutilisée ne coûte rien
timings-blur = préfiltrage de la carte
timings-blur-tip = GPU : flou des moments VSM/EVSM/MSM, ou étendue des profondeurs par blocs de la carte, qui permet au PCF de trancher d'une seule lecture les pixels entièrement éclairés ou entièrement dans l'ombre
timings-shading = ombrage
timings-shading-tip = GPU : la passe caméra (BRDF, éclairement, lectures de la carte d'ombres)
timings-display = affichage
timings-display-tip = GPU : exposition, fausses couleurs, sRGB
timings-gpu-total = total GPU
timings-gpu-total-tip = Somme des passes chronométrées
timings-shadow-map = carte d'ombres
timings-redrawn = retracée à cette image
timings-reused = réutilisée
timings-reused-ranges = réutilisée ; le filtre lit ses étendues de profondeur (blocs de { $block } texels)
timings-unused = non tracée : V tracé par rayons ne lit aucune carte d'ombres
timings-shadow-map-tip = Retracée seulement quand la lumière, la géométrie ou les réglages d'ombre changent. Une carte réutilisée reçoit ses étendues de profondeur (profondeurs la plus proche et la plus lointaine par bloc de texels) : le PCF et le disque de Poisson tranchent alors d'une seule lecture un pixel entièrement éclairé ou entièrement dans l'ombre, au lieu de tester chacun de leurs échantillons
timings-layout = disposition
timings-layout-tip = Un frustum ajusté à la scène, ou les faces du cube qui voient de la géométrie
timings-casters = objets projetant une ombre
timings-casters-value = { $drawn } sur { $total } ({ $layers })
timings-casters-tip = Objets tracés dans chaque couche : seulement ceux qui peuvent ombrer un récepteur visible
timings-resolution = résolution
timings-resolution-tip = Texels par côté de la carte d'ombres utilisés
timings-near-far = proche / lointain
timings-near-far-tip = L'intervalle de profondeur de la caméra, ajusté à la scène
timings-visible-objects = objets visibles
timings-visible-objects-tip = Objets dans le frustum de la caméra
timings-adapter = adaptateur : { $adapter }
timings-adapter-tip = L'adaptateur GPU, son API graphique et son pilote
timings-backend = API graphique
timings-backend-tip = L'API graphique sur laquelle wgpu s'exécute (WGPU_BACKEND la choisit)
timings-max-texture = texture max.
timings-max-texture-tip = Le plus grand côté de texture 2D de ce périphérique
timings-timestamps = horodatages
timings-timestamps-yes = oui
timings-timestamps-no = non (temps GPU indisponibles)
timings-timestamps-tip = Les requêtes d'horodatage donnent les temps GPU de chaque passe

## Colour panel (colour.rs)

colour-model = Modèle
colour-spectral = spectral
colour-spectral-tip = XYZ = Σ S(λ) R(λ) (x̄, ȳ, z̄)(λ) Δλ, mis à l'échelle pour qu'un blanc parfait ait la luminance de la couleur de la lumière, puis converti en sRGB linéaire
colour-rgb-approx = approximation RVB
colour-rgb-approx-tip = Le produit du cours : (sRGB linéaire de la lumière à Y = 1) × luminance de la couleur de la lumière × couleur de base, canal par canal
colour-material = Matériau
colour-material-tip = Sa réflectance R(λ) : mesurée pour une pastille de ColorChecker, sinon reconstruite à partir de la couleur de base (Jakob & Hanika 2019)
colour-illuminant = Illuminant
colour-illuminant-tip = Le spectre S(λ) de la lumière (tables CIE 015:2018, ou Planck). Il conserve la luminance de la couleur de la lumière : seule la chromaticité change
colour-no-spectrum = RVB (sans spectre)
colour-no-spectrum-tip = La couleur RVB de la lumière multipliée par chaque couleur de base : le modèle du cours
colour-d65-tip = CIE D65, lumière du jour moyenne
colour-a-tip = CIE A, lampe à incandescence au tungstène (2856 K)
colour-fl2-tip = CIE FL2, fluorescent blanc froid
colour-fl11-tip = CIE FL11, fluorescent à trois bandes
colour-led-b3-tip = CIE LED-B3, LED blanche à luminophore
colour-blackbody-at = Radiateur de Planck à { $temperature }
colour-blackbody = corps noir
colour-blackbody-tip = Loi de Planck : M(λ, T) ∝ λ⁻⁵ / (exp(c₂ / λT) − 1)
colour-temperature = température T
colour-temperature-tip = Température de couleur du radiateur de Planck (K)
colour-relative = relatif
colour-rgb-product = produit RVB
colour-xyz-tip = XYZ spectral = k Σ S R (x̄, ȳ, z̄), k = 100 / Σ S ȳ ; ΔE2000 (CIE 2001) entre le résultat spectral et le produit RVB dans CIE Lab, le blanc de l'illuminant servant de référence
colour-delta-e-invisible = sous 1 : invisible
colour-delta-e-visible = de 1 à 3 : visible côte à côte
colour-delta-e-different = au-dessus de 3 : une autre couleur

## Tour and dropped files (lab/tour.rs, lab/jobs.rs)

scene-lecture-spheres = sphères du cours
tour-status = visite { $step }/{ $count } : { $title } (Ctrl+Z pour annuler)
status-drop-unknown = « { $path } » : déposez un fichier .gltf, .glb ou .toml

## Split view labels (names.rs)
compare-norm = normalisation { $value }
compare-filter = filtre { $value }
compare-resolution = carte d'ombres { $texels }²
compare-bias = biais { $value }
compare-shadow-map = carte d'ombres
compare-ray-traced = lancer de rayons
compare-rgb-approx = approximation RVB
compare-spectral = spectral

## Split choices (names.rs)
split-choice-norm = normalisation none | approx
split-choice-filter = filtre none | PCF
split-choice-pcss = filtre PCF | PCSS
split-choice-resolution = résolution 256² | 2048²
split-choice-visibility = carte d'ombres | lancer de rayons
split-choice-colour = RVB | spectral
