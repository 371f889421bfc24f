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
